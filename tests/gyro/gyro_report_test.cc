// The gyroscope outside its solver: the turns scored from a calibration read
// back (for the report) agree with the solver's own, the report's gyroscope
// section shows them, and the scale's directional derivative matches the
// full Jacobian.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "gyro/rotation.h"
#include "mpcal/calibrate.h"
#include "mpcal/gyro.h"
#include "mpcal/report.h"
#include "mpcal/simulate.h"

namespace mpcal {
namespace {

SimulatedSession ImuSession(std::uint64_t seed) {
  SimulateStaticOptions o;
  o.device = FindPreset("colibri");
  o.device.range_mps2 = 0.0;
  o.seed = seed;
  o.dwell_s = 5.0;
  o.gyro = true;
  return SimulateStatic(o);
}

TEST(ScoreGyroTurns, AgreesWithTheSolversTurns) {
  const SimulatedSession s = ImuSession(21);
  const CalibrateResult r = CalibrateRecording(s.recording, {});
  ASSERT_TRUE(r.gyro && r.gyro->converged());
  const std::vector<GyroTurn> scored = ScoreGyroTurns(
      s.recording, r.detection.intervals, r.calibration, r.gyro->calibration);
  ASSERT_EQ(scored.size(), r.gyro->turns.size());
  for (std::size_t k = 0; k < scored.size(); ++k) {
    const GyroTurn& a = scored[k];
    const GyroTurn& b = r.gyro->turns[k];
    EXPECT_EQ(a.begin, b.begin);
    EXPECT_EQ(a.end, b.end);
    EXPECT_NEAR(a.residual_before_rad, b.residual_before_rad, 1e-9);
    EXPECT_NEAR(a.residual_after_rad, b.residual_after_rad, 1e-9);
    EXPECT_NEAR(a.angle_rad, b.angle_rad, 1e-9);
    EXPECT_GT(a.sigma_rad, 0.0);
  }
}

TEST(GyroReport, SectionShowsTheMatrixTheTurnsAndTheirAxes) {
  const SimulatedSession s = ImuSession(22);
  const CalibrateResult r = CalibrateRecording(s.recording, {});
  ASSERT_TRUE(r.calibration.gyroscope.has_value());
  ReportInputs in;
  in.calibration = r.calibration;
  in.session = ReportSession{s.recording, r.detection};
  in.generated_at = "test";
  const std::string html = RenderReport(in);
  EXPECT_NE(html.find("<section id=\"gyroscope\">"), std::string::npos);
  EXPECT_NE(html.find("Misalignment, row x"), std::string::npos);
  EXPECT_NE(html.find("Tilt residual of each turn before calibration"),
            std::string::npos);
  EXPECT_NE(html.find("Tilt residual of each turn after calibration"), std::string::npos);
  EXPECT_NE(html.find("Axes of the turns on the sphere"), std::string::npos);
  // Without the session: the matrix and the biases, no turns.
  in.session.reset();
  const std::string alone = RenderReport(in);
  EXPECT_NE(alone.find("<section id=\"gyroscope\">"), std::string::npos);
  EXPECT_EQ(alone.find("Tilt residual of each turn"), std::string::npos);
  // An accelerometer-only calibration has no gyroscope section.
  in.calibration->gyroscope.reset();
  EXPECT_EQ(RenderReport(in).find("id=\"gyroscope\""), std::string::npos);
}

TEST(GyroRotation, DerivativeAlongADirectionIsTheJacobianTimesIt) {
  std::vector<internal::TurnStep> steps;
  for (int i = 0; i < 150; ++i) {
    steps.push_back(
        {Eigen::Vector3d(0.02 * std::sin(0.07 * i), 0.01, 0.015 * std::cos(0.05 * i)),
         Eigen::Vector3d(0.02 * std::sin(0.07 * i + 0.07),
                         0.011,
                         0.015 * std::cos(0.05 * i + 0.05))});
  }
  Eigen::Matrix3d m;
  m << 1.02, 0.01, -0.02, 0.015, 0.98, 0.03, -0.01, 0.02, 1.01;
  Eigen::Matrix3d d;
  d << 1.0, 0.3, -0.2, 0.1, 0.7, 0.4, -0.5, 0.2, 1.1;
  Eigen::Matrix<double, 3, 9> full;
  const Eigen::Matrix3d r = internal::RotationOverTurn(m, steps, &full);
  Eigen::Vector3d along;
  const Eigen::Matrix3d r2 = internal::RotationOverTurnAlong(m, steps, d, &along);
  EXPECT_LT((r - r2).norm(), 1e-14);
  const Eigen::Matrix<double, 3, 3, Eigen::RowMajor> d_rows = d;
  const Eigen::Map<const Eigen::Matrix<double, 9, 1>> d_vec(d_rows.data());
  EXPECT_LT((full * d_vec - along).norm(), 1e-12 * (1.0 + along.norm()));
}

}  // namespace
}  // namespace mpcal
