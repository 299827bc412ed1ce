// The gyroscope's anchor: imu_tk's Xsens recording, accelerometer and
// gyroscope in two files of raw counts merged by row. imu_tk's own
// parameters carry gravity over the 37 turns to 0.57° RMS (0.34° with a bias
// measured at every position); an independent general-M fit reaches 0.31°.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "mpcal/calibrate.h"
#include "mpcal/error.h"
#include "mpcal/gyro_log.h"
#include "mpcal/log_reader.h"
#include "test_util.h"

namespace mpcal {
namespace {

using testing::kDeg;

Recording XsensImu() {
  LogOptions options;
  options.units = AccelUnits::kCounts;
  Recording r =
      ReadLog(testing::RealDataPath("xsens-multiposition/xsens_acc.mat"), options);
  const Recording g =
      ReadLog(testing::RealDataPath("xsens-multiposition/xsens_gyro.mat"), options);
  MergeGyroLog(r, g, GyroUnits::kCounts);
  return r;
}

TEST(XsensGyroscope, CarriesGravityOverTheTurnsBetterThanImuTk) {
  CalibrateOptions options;
  options.solve.gravity_mps2 = 9.81744;
  const CalibrateResult r = CalibrateRecording(XsensImu(), options);
  ASSERT_TRUE(r.gyro.has_value());
  ASSERT_TRUE(r.gyro->converged()) << r.gyro->message;
  ASSERT_TRUE(r.calibration.gyroscope.has_value());
  const GyroCalibration& g = *r.calibration.gyroscope;
  EXPECT_EQ(g.fit->turns, 37);
  // The target (imu_tk: 0.57°): 0.14° with the bias's g-sensitivity,
  // which the biases at the positions show (F far above chance).
  EXPECT_LE(g.fit->residual_rms_after_rad, 0.33 * kDeg);
  EXPECT_TRUE(g.g_sensitivity_radps_per_mps2.has_value());
  EXPECT_GT(r.gyro->g_sensitivity_f, 50.0);
  EXPECT_LT(g.fit->variance_factor, 2.0);
  EXPECT_GT(g.fit->residual_rms_before_rad, 3.0 * g.fit->residual_rms_after_rad);
  // imu_tk's K: about 2.09e-4 rad/s per count on every axis, found from the
  // turns alone; its zero about 32768 counts.
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(g.m(i, i) * g.radps_per_unit, 2.095e-4, 0.02 * 2.095e-4) << "axis " << i;
    EXPECT_NEAR(g.bias_radps[i] / g.radps_per_unit, 32600.0, 300.0) << "axis " << i;
  }
  // Misalignment within imu_tk's 0.06 rad of it, each 1σ well below that.
  EXPECT_LT(g.MStd().maxCoeff(), 0.01);
}

TEST(XsensGyroscope, WithoutGSensitivityTheBiasLeaksIntoTheTurns) {
  CalibrateOptions options;
  options.solve.gravity_mps2 = 9.81744;
  options.gyro.g_sensitivity = GSensitivity::kOff;
  const CalibrateResult r = CalibrateRecording(XsensImu(), options);
  ASSERT_TRUE(r.gyro && r.gyro->converged());
  // Still better than imu_tk's 0.57° with its constant bias.
  EXPECT_LT(r.gyro->calibration.fit->residual_rms_after_rad, 0.45 * kDeg);
  EXPECT_GT(r.gyro->calibration.fit->residual_rms_after_rad, 0.30 * kDeg);
}

// Rows that differ (a stamp moved, a row short) are two streams: the
// gyroscope is put on the accelerometer's stamps, not refused; a gyroscope
// is joined once.
TEST(XsensGyroscope, TheGyroscopeFileJoinsOnceEvenWhenItsRowsDiffer) {
  LogOptions options;
  options.units = AccelUnits::kCounts;
  const Recording acc =
      ReadLog(testing::RealDataPath("xsens-multiposition/xsens_acc.mat"), options);
  Recording g =
      ReadLog(testing::RealDataPath("xsens-multiposition/xsens_gyro.mat"), options);
  Recording shifted = g;
  shifted.time_s[100] += 0.005;
  Recording joined = acc;
  MergeGyroLog(joined, shifted, GyroUnits::kCounts);
  EXPECT_EQ(joined.gyro_radps.size(), joined.accel.size());
  Recording r = acc;
  MergeGyroLog(r, g, GyroUnits::kCounts);
  EXPECT_EQ(r.gyro_units, GyroUnits::kCounts);
  EXPECT_EQ(r.gyro_radps.size(), acc.accel.size());
  EXPECT_THROW(MergeGyroLog(r, g, GyroUnits::kCounts), Error);
}

}  // namespace
}  // namespace mpcal
