// The factorisations between mpcal's lower-triangular model and the tools'
// matrices, and the model recovered from its correction.
#include <random>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "export/triad.h"
#include "mpcal/error.h"

namespace mpcal::export_formats {
namespace {

Eigen::Matrix3d RandomMatrix(std::mt19937& rng) {
  std::normal_distribution<double> n(0.0, 0.05);
  Eigen::Matrix3d m = Eigen::Matrix3d::Identity();
  for (int i = 0; i < 9; ++i) m(i / 3, i % 3) += n(rng);
  return m;
}

void ExpectRotation(const Eigen::Matrix3d& r) {
  EXPECT_LT((r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(),
            1e-14);
  EXPECT_NEAR(r.determinant(), 1.0, 1e-14);
}

TEST(ExportTriad, FactorsReconstructTheMatrix) {
  std::mt19937 rng(7);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::Matrix3d m = RandomMatrix(rng);
    const Factored ru = RotationTimesUpper(m);
    const Factored rl = RotationTimesLower(m);
    const Factored lr = LowerTimesRotation(m);
    EXPECT_LT((ru.rotation * ru.triangular - m).cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_LT((rl.rotation * rl.triangular - m).cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_LT((lr.triangular * lr.rotation - m).cwiseAbs().maxCoeff(), 1e-14);
    for (const Factored* f : {&ru, &rl, &lr}) {
      ExpectRotation(f->rotation);
      EXPECT_GT(f->triangular.diagonal().minCoeff(), 0.0);
    }
    EXPECT_LT(ru.triangular.triangularView<Eigen::StrictlyLower>()
                  .toDenseMatrix()
                  .cwiseAbs()
                  .maxCoeff(),
              1e-15);
    EXPECT_LT(rl.triangular.triangularView<Eigen::StrictlyUpper>()
                  .toDenseMatrix()
                  .cwiseAbs()
                  .maxCoeff(),
              1e-15);
    EXPECT_LT(lr.triangular.triangularView<Eigen::StrictlyUpper>()
                  .toDenseMatrix()
                  .cwiseAbs()
                  .maxCoeff(),
              1e-15);
  }
}

TEST(ExportTriad, ModelOfLowerInvertsTheCorrection) {
  Calibration c;
  c.input_units = AccelUnits::kCounts;
  c.mps2_per_unit = 9.80665 / 4096.0;
  c.model.bias_mps2 = Eigen::Vector3d(0.12, -0.05, 0.31);
  c.model.scale_factor_error = Eigen::Vector3d(0.01, -0.004, 0.02);
  c.model.theta_yz_rad = 0.003;
  c.model.theta_zx_rad = -0.006;
  c.model.theta_zy_rad = 0.009;
  const AccelAffine a = AccelOf(c);
  const ErrorModel back = ModelOfLower(a.linear, a.offset, c.mps2_per_unit);
  EXPECT_LT((back.bias_mps2 - c.model.bias_mps2).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_LT((back.scale_factor_error - c.model.scale_factor_error).cwiseAbs().maxCoeff(),
            1e-13);
  EXPECT_NEAR(back.theta_yz_rad, c.model.theta_yz_rad, 1e-14);
  EXPECT_NEAR(back.theta_zx_rad, c.model.theta_zx_rad, 1e-14);
  EXPECT_NEAR(back.theta_zy_rad, c.model.theta_zy_rad, 1e-14);
  // And the affine form is the correction itself.
  const Eigen::Vector3d raw(2100.0, -3300.0, 1200.0);
  EXPECT_LT((a.linear * (raw - a.offset) - c.Correct(raw)).cwiseAbs().maxCoeff(), 1e-12);
}

TEST(ExportTriad, ChecksRefuseWhatIsNotACalibration) {
  Eigen::Matrix3d singular = Eigen::Matrix3d::Identity();
  singular(2, 2) = 0.0;
  EXPECT_THROW(CheckInvertible(singular, "m"), Error);
  EXPECT_NO_THROW(CheckInvertible(Eigen::Matrix3d::Identity(), "m"));
  Eigen::Matrix3d not_rotation = Eigen::Matrix3d::Identity();
  not_rotation(0, 1) = 0.01;
  EXPECT_THROW(CheckRotation(not_rotation, "r"), Error);
  EXPECT_THROW(CheckRotation(-Eigen::Matrix3d::Identity(), "r"), Error);  // det −1
  EXPECT_THROW(CheckTriangular(not_rotation, true, "m"), Error);
  EXPECT_NO_THROW(CheckTriangular(not_rotation, false, "m"));
}

}  // namespace
}  // namespace mpcal::export_formats
