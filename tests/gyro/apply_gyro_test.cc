// `apply` with the simulator's truth file returns the true angular rate
// along every turn to the noise level, in rad/s or deg/s, from rad/s or raw
// counts; the IMU file round-trips.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "mpcal/apply.h"
#include "mpcal/calibrate.h"
#include "mpcal/calibration_file.h"
#include "mpcal/error.h"
#include "mpcal/log_reader.h"
#include "mpcal/log_writer.h"
#include "mpcal/simulate.h"
#include "test_util.h"

namespace mpcal {
namespace {

// RMS over the turn samples (not the still parts) of corrected − true rate,
// per axis, over the per-sample noise after M.
double TurnErrorOverNoise(const SimulatedSession& s,
                          const Recording& corrected,
                          double out_per_radps) {
  const GyroCalibration& truth = *s.truth.gyroscope;
  double sum = 0.0;
  double noise = 0.0;
  std::size_t n = 0;
  std::size_t k = 0;
  for (std::size_t i = 0; i < s.recording.size(); ++i) {
    while (k < s.still_ranges.size() && i >= s.still_ranges[k].second) ++k;
    const bool still = k < s.still_ranges.size() && i >= s.still_ranges[k].first;
    if (still ||
        i < s.still_ranges.front().first - static_cast<std::size_t>(2 * s.rate_hz)) {
      continue;
    }
    sum += (corrected.gyro_radps[i] / out_per_radps - s.true_rate_radps[i]).squaredNorm();
    ++n;
  }
  for (int r = 0; r < 3; ++r) noise += truth.m.row(r).squaredNorm();
  noise *= s.gyro_noise_std_radps * s.gyro_noise_std_radps;
  return std::sqrt(sum / static_cast<double>(n) / noise);
}

SimulatedSession Session(GyroUnits units) {
  SimulateStaticOptions o;
  o.device = FindPreset("colibri");
  o.seed = 21;
  o.dwell_s = 4.0;
  o.gyro = true;
  o.gyro_units = units;
  return SimulateStatic(o);
}

TEST(ApplyGyroscope, TruthFileReturnsTheTrueRateAlongEveryTurn) {
  testing::ScratchDir dir;
  const SimulatedSession s = Session(GyroUnits::kRadps);
  LogWriteOptions write;
  write.significant_digits = 0;
  WriteRecordingFile(dir.Path("s.csv"), s.recording, write);
  WriteCalibrationFile(dir.Path("truth.json"), s.truth);
  const Calibration truth = ReadCalibrationFile(dir.Path("truth.json"));
  ASSERT_TRUE(truth.gyroscope.has_value());
  EXPECT_NE(testing::ReadFile(dir.Path("truth.json")).find("\"mpcal.imu/1\""),
            std::string::npos);

  ApplyOptions options;
  const ApplyResult r =
      ApplyCalibration(truth, dir.Path("s.csv"), dir.Path("out.csv"), options);
  EXPECT_TRUE(r.gyro_corrected);
  const Recording out = ReadLog(dir.Path("out.csv"), {});
  ASSERT_EQ(out.gyro_radps.size(), s.recording.size());
  // White noise through M, and nothing else (a bias of 1 deg/s would be
  // five times the noise).
  EXPECT_NEAR(TurnErrorOverNoise(s, out, 1.0), 1.0, 0.05);
  EXPECT_GT(TurnErrorOverNoise(s, s.recording, 1.0), 3.0);

  options.out_gyro_units = GyroUnits::kDps;
  ApplyCalibration(truth, dir.Path("s.csv"), dir.Path("out_dps.csv"), options);
  const Recording dps = ReadLog(dir.Path("out_dps.csv"), {});
  EXPECT_NEAR(TurnErrorOverNoise(s, dps, 180.0 / std::numbers::pi), 1.0, 0.05);
}

TEST(ApplyGyroscope, RawCountsComeOutInRadPerSecond) {
  testing::ScratchDir dir;
  const SimulatedSession s = Session(GyroUnits::kCounts);
  WriteRecordingFile(dir.Path("s.csv"), s.recording, {});
  WriteCalibrationFile(dir.Path("truth.json"), s.truth);
  const Calibration truth = ReadCalibrationFile(dir.Path("truth.json"));
  ApplyOptions options;
  options.log.gyro_in_counts = true;
  const ApplyResult r =
      ApplyCalibration(truth, dir.Path("s.csv"), dir.Path("out.csv"), options);
  EXPECT_EQ(r.out_gyro_units, GyroUnits::kRadps);
  const Recording out = ReadLog(dir.Path("out.csv"), {});
  EXPECT_NEAR(TurnErrorOverNoise(s, out, 1.0), 1.0, 0.05);
  // A counts calibration refuses a log read in rad/s.
  options.log.gyro_in_counts = false;
  EXPECT_THROW(ApplyCalibration(truth, dir.Path("s.csv"), dir.Path("bad.csv"), options),
               Error);
}

TEST(ImuFile, RoundTripsTheGyroscopeAndStillReadsAccelerometerFiles) {
  Calibration c;
  GyroCalibration g;
  g.input_units = GyroUnits::kCounts;
  g.radps_per_unit = 2.09e-4;
  g.m << 1.01, 0.002, -0.003, 0.004, 0.99, 0.005, -0.006, 0.007, 1.002;
  g.bias_radps = {6.85, 6.78, 6.79};
  g.bias_std_radps = Eigen::Vector3d(1e-5, 2e-5, 3e-5);
  Eigen::Matrix<double, 9, 9> cov = Eigen::Matrix<double, 9, 9>::Identity() * 1e-8;
  cov(0, 1) = cov(1, 0) = 2e-9;
  g.m_covariance = cov;
  g.position_bias = {{1.0, {6.84, 6.78, 6.79}}, {9.0, {6.86, 6.78, 6.79}}};
  GyroFitSummary fit;
  fit.turns = 12;
  fit.residual_rms_before_rad = 0.1;
  fit.residual_rms_after_rad = 0.005;
  fit.converged = true;
  fit.variance_factor = 1.3;
  g.fit = fit;
  c.gyroscope = g;
  const Calibration back = CalibrationFromJson(CalibrationToJson(c), "mem");
  ASSERT_TRUE(back.gyroscope.has_value());
  EXPECT_EQ(back.gyroscope->input_units, GyroUnits::kCounts);
  EXPECT_TRUE(back.gyroscope->m.isApprox(g.m, 1e-15));
  EXPECT_TRUE(back.gyroscope->m_covariance->isApprox(cov, 1e-15));
  EXPECT_EQ(back.gyroscope->position_bias.size(), 2u);
  EXPECT_NEAR(back.gyroscope->BiasChangeRadps().x(), 0.02, 1e-12);
  EXPECT_DOUBLE_EQ(back.gyroscope->fit->variance_factor, 1.3);

  c.gyroscope.reset();
  const std::string accel_only = CalibrationToJson(c);
  EXPECT_NE(accel_only.find("\"mpcal.accelerometer/1\""), std::string::npos);
  EXPECT_FALSE(CalibrationFromJson(accel_only, "mem").gyroscope.has_value());
  // An IMU file without its gyroscope block is refused.
  std::string broken = accel_only;
  broken.replace(broken.find("mpcal.accelerometer/1"), 21, "mpcal.imu/1");
  EXPECT_THROW(CalibrationFromJson(broken, "mem"), Error);
}

// A log in deg/s is held in rad/s; the calibration made from it records the
// log's units (dps, π/180 rad/s per unit), so that it corrects the log as
// written: the same M and bias as from the log in rad/s, and the same rates.
TEST(CalibrateGyroscope, ALogInDegreesPerSecondIsRecordedAsSuch) {
  const SimulatedSession s = Session(GyroUnits::kRadps);
  Recording dps = s.recording;
  dps.gyro_log_units = GyroUnits::kDps;  // as ReadLog holds a log in deg/s
  const CalibrateResult in_rads = CalibrateRecording(s.recording, {});
  const CalibrateResult in_dps = CalibrateRecording(dps, {});
  ASSERT_TRUE(in_rads.calibration.gyroscope);
  ASSERT_TRUE(in_dps.calibration.gyroscope);
  const GyroCalibration& r = *in_rads.calibration.gyroscope;
  const GyroCalibration& d = *in_dps.calibration.gyroscope;
  EXPECT_EQ(r.input_units, GyroUnits::kRadps);
  EXPECT_DOUBLE_EQ(r.radps_per_unit, 1.0);
  EXPECT_EQ(d.input_units, GyroUnits::kDps);
  EXPECT_DOUBLE_EQ(d.radps_per_unit, std::numbers::pi / 180.0);
  EXPECT_TRUE(d.m.isApprox(r.m, 1e-12));
  EXPECT_TRUE(d.bias_radps.isApprox(r.bias_radps, 1e-12));
  // A turn's reading (rad/s held), as the log writes it in deg/s.
  const std::size_t i = s.still_ranges[3].second + static_cast<std::size_t>(s.rate_hz);
  const Eigen::Vector3d held = s.recording.gyro_radps[i];
  ASSERT_GT(held.norm(), 0.1);
  EXPECT_LT((d.Correct(held * 180.0 / std::numbers::pi) - r.Correct(held)).norm(), 1e-12);
  // And the file keeps it.
  const Calibration back =
      CalibrationFromJson(CalibrationToJson(in_dps.calibration), "dps.json");
  EXPECT_EQ(back.gyroscope->input_units, GyroUnits::kDps);
}

}  // namespace
}  // namespace mpcal
