#include "mpcal/model.h"

#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mpcal/calibration.h"

namespace mpcal {
namespace {

constexpr double kRoundTripTolerance = 1e-12;  // m/s², double rounding

ErrorModel ConsumerGradeModel() {
  ErrorModel m;
  m.bias_mps2 = {0.3 * 9.8, -0.2 * 9.8, 0.25 * 9.8};
  m.scale_factor_error = {0.06, -0.04, 0.05};
  m.theta_yz_rad = 0.02;
  m.theta_zx_rad = -0.015;
  m.theta_zy_rad = 0.01;
  return m;
}

TEST(ErrorModel, DefaultIsIdealSensor) {
  const ErrorModel ideal;
  const Eigen::Vector3d y(1.0, -2.0, 9.8);
  EXPECT_TRUE(ideal.Correct(y).isApprox(y));
  EXPECT_TRUE(ideal.Forward(y).isApprox(y));
  EXPECT_TRUE(ideal.NonOrthogonality().isIdentity());
}

TEST(ErrorModel, CorrectInvertsForward) {
  const ErrorModel m = ConsumerGradeModel();
  std::mt19937 rng(7);
  std::normal_distribution<double> n(0.0, 10.0);
  for (int i = 0; i < 100; ++i) {
    const Eigen::Vector3d a(n(rng), n(rng), n(rng));
    EXPECT_LT((m.Correct(m.Forward(a)) - a).norm(), kRoundTripTolerance);
    EXPECT_LT((m.Forward(m.Correct(a)) - a).norm(), kRoundTripTolerance);
  }
}

TEST(ErrorModel, CorrectIsTheMatrixFormOfEquations8To10) {
  // a = T diag(1/(1+s)) (Y - b), docs/method.md §2.1.
  const ErrorModel m = ConsumerGradeModel();
  const Eigen::Vector3d y(3.0, -1.0, 8.0);
  const Eigen::Vector3d expected =
      m.NonOrthogonality() *
      (y - m.bias_mps2).cwiseQuotient(Eigen::Vector3d::Ones() + m.scale_factor_error);
  EXPECT_LT((m.Correct(y) - expected).norm(), kRoundTripTolerance);
}

TEST(Calibration, AffineCorrectionIsCorrect) {
  // Raw counts, so that the unit factor is in the map too.
  Calibration c;
  c.model = ConsumerGradeModel();
  c.mps2_per_unit = 1.0 / 1670.0;
  const Calibration::AffineCorrection affine = c.Affine();
  for (const Eigen::Vector3d& y : {Eigen::Vector3d(33000.0, 31000.0, 36000.0),
                                   Eigen::Vector3d(0.0, 0.0, 0.0),
                                   Eigen::Vector3d(-16000.0, 250.0, 18000.0)}) {
    EXPECT_LT((affine(y) - c.Correct(y)).norm(), kRoundTripTolerance);
  }
}

TEST(ErrorModel, XAxisIsUntouchedByTheAngles) {
  // The frame is defined by the x sensor axis: no angle moves ax.
  ErrorModel m;
  m.theta_yz_rad = 0.1;
  m.theta_zx_rad = 0.2;
  m.theta_zy_rad = 0.3;
  const Eigen::Vector3d y(2.0, 3.0, 4.0);
  EXPECT_DOUBLE_EQ(m.Correct(y).x(), 2.0);
}

TEST(ErrorModel, PackingRoundTrips) {
  const ErrorModel m = ConsumerGradeModel();
  const ErrorModel back = FromVector(ToVector(m));
  EXPECT_EQ(ToVector(back), ToVector(m));
}

TEST(ModelKind, NamesRoundTrip) {
  for (ModelKind k : {ModelKind::kShinElSheimy9, ModelKind::kBiasScale6}) {
    EXPECT_EQ(ParseModelKind(ToString(k)), k);
  }
  EXPECT_EQ(ParseModelKind("twelve"), std::nullopt);
  EXPECT_EQ(ParameterCount(ModelKind::kShinElSheimy9), 9);
  EXPECT_EQ(ParameterCount(ModelKind::kBiasScale6), 6);
}

}  // namespace
}  // namespace mpcal
