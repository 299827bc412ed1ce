// Two streams at two rates: the gyroscope put on the accelerometer's stamps
// keeps the angle turned between rows; rows outside the gyroscope's span are
// dropped; streams that do not overlap are refused; a recording's clock
// origin is added before the times are compared.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mpcal/error.h"
#include "mpcal/gyro_log.h"

namespace mpcal {
namespace {

using ::testing::HasSubstr;

// One turn about z: ω(t) = A sin²(π (t − 1) / T) for 1 ≤ t ≤ 1 + T, else 0;
// its angle from 0 to t is A ((t−1)/2 − T sin(2π(t−1)/T) / (4π)).
constexpr double kTurnA = 2.0;  // rad/s
constexpr double kTurnT = 0.8;  // s
double TurnRate(double t) {
  if (t < 1.0 || t > 1.0 + kTurnT) return 0.0;
  const double s = std::sin(std::numbers::pi * (t - 1.0) / kTurnT);
  return kTurnA * s * s;
}
double TurnAngle(double t) {
  const double u = std::clamp(t - 1.0, 0.0, kTurnT);
  return kTurnA * (u / 2.0 - kTurnT * std::sin(2.0 * std::numbers::pi * u / kTurnT) /
                                 (4.0 * std::numbers::pi));
}

Recording StreamAt(double rate_hz, double start_s, double end_s, bool gyro) {
  Recording r;
  r.source = gyro ? "gyro" : "accel";
  for (int k = 0;; ++k) {
    const double t = start_s + k / rate_hz;
    if (t > end_s) break;
    r.time_s.push_back(t);
    r.accel.push_back(gyro ? Eigen::Vector3d(0.0, 0.0, TurnRate(t))
                           : Eigen::Vector3d(0.0, 0.0, 9.8));
  }
  return r;
}

// The trapezoid over the merged rows, as the turn integration sums them.
double TrapezoidAngle(const Recording& r) {
  double angle = 0.0;
  for (std::size_t i = 1; i < r.size(); ++i) {
    angle += 0.5 * (r.gyro_radps[i - 1].z() + r.gyro_radps[i].z()) *
             (r.time_s[i] - r.time_s[i - 1]);
  }
  return angle;
}

TEST(MergeTwoStreams, TheGyroscopeOnTheAccelerometersStampsKeepsTheTurnsAngle) {
  for (const double accel_hz : {63.0, 250.0}) {
    for (const double gyro_hz : {200.0, 400.0}) {
      Recording rec = StreamAt(accel_hz, 0.0, 3.0, false);
      const Recording gyro = StreamAt(gyro_hz, 0.0031, 3.0, true);
      const std::size_t rows = rec.size();
      const StreamMerge m = MergeGyroLog(rec, gyro, GyroUnits::kRadps);
      EXPECT_TRUE(m.resampled);
      EXPECT_NEAR(m.accel_rate_hz, accel_hz, 1e-6 * accel_hz);
      EXPECT_NEAR(m.gyro_rate_hz, gyro_hz, 1e-6 * gyro_hz);
      EXPECT_EQ(m.rows_dropped_before, 1u);  // row 0 is before the gyroscope's first
      EXPECT_EQ(rec.size() + m.rows_dropped_before + m.rows_dropped_after, rows);
      ASSERT_EQ(rec.gyro_radps.size(), rec.size());
      // The whole turn's angle, 0.8 rad: the gyroscope's samples hold it to
      // the trapezoid's error at its own rate, A (π/T)² dt² T / 12 (below
      // 1e-4 rad at 200 Hz), whatever the accelerometer's rate.
      const double want = TurnAngle(3.0);
      EXPECT_NEAR(TrapezoidAngle(rec), want, 2e-4) << accel_hz << " Hz / " << gyro_hz;
      // Row by row, each rate is the turn's mean over the row's interval.
      for (std::size_t i = 1; i + 1 < rec.size(); ++i) {
        const double lo = 0.5 * (rec.time_s[i - 1] + rec.time_s[i]);
        const double hi = 0.5 * (rec.time_s[i] + rec.time_s[i + 1]);
        const double mean = (TurnAngle(hi) - TurnAngle(lo)) / (hi - lo);
        ASSERT_NEAR(rec.gyro_radps[i].z(), mean, 0.01) << "row " << i;
      }
      EXPECT_TRUE(m.findings.empty());
      // The gyroscope's own samples are kept, on the accelerometer's clock:
      // the turns are integrated over them (turn_problem.h, SamplesOf).
      ASSERT_EQ(rec.gyro_samples.size(), gyro.size());
      ASSERT_EQ(rec.gyro_samples_time_s.size(), gyro.size());
      for (std::size_t k = 0; k < gyro.size(); ++k) {
        ASSERT_EQ(rec.gyro_samples_time_s[k], gyro.time_s[k]);
        ASSERT_EQ(rec.gyro_samples[k], gyro.accel[k]);
      }
    }
  }
}

TEST(MergeTwoStreams, RowsOutsideTheGyroscopesSpanAreDroppedAndReported) {
  Recording rec = StreamAt(100.0, 0.0, 10.0, false);
  const Recording gyro = StreamAt(200.0, 2.0, 5.0, true);
  const StreamMerge m = MergeGyroLog(rec, gyro, GyroUnits::kRadps);
  EXPECT_EQ(m.rows_dropped_before, 200u);
  EXPECT_EQ(m.rows_dropped_after, 500u);
  EXPECT_NEAR(rec.time_s.front(), 2.0, 1e-9);
  EXPECT_NEAR(rec.time_s.back(), 5.0, 1e-9);
  EXPECT_THAT(m.findings, ::testing::ElementsAre(StreamFinding::kSpansDiffer));
}

TEST(MergeTwoStreams, AGapInTheGyroscopeIsAFinding) {
  Recording rec = StreamAt(100.0, 0.0, 4.0, false);
  Recording gyro = StreamAt(200.0, 0.0, 4.0, true);
  // 0.1 s (20 samples) missing from 2 s on.
  gyro.time_s.erase(gyro.time_s.begin() + 401, gyro.time_s.begin() + 420);
  gyro.accel.erase(gyro.accel.begin() + 401, gyro.accel.begin() + 420);
  const StreamMerge m = MergeGyroLog(rec, gyro, GyroUnits::kRadps);
  EXPECT_NEAR(m.gyro_gap_s, 0.1, 1e-9);
  EXPECT_NEAR(m.gyro_gap_at_s, 2.0, 1e-9);
  EXPECT_THAT(m.findings, ::testing::ElementsAre(StreamFinding::kGyroGap));
}

TEST(MergeTwoStreams, StreamsThatDoNotOverlapAreRefusedWithBothSpans) {
  Recording rec = StreamAt(100.0, 0.0, 10.0, false);
  const Recording gyro = StreamAt(200.0, 20.0, 30.0, true);
  try {
    MergeGyroLog(rec, gyro, GyroUnits::kRadps);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInput);
    EXPECT_THAT(e.what(),
                HasSubstr("gyro spans 20.000000 to 30.000000 s and accel spans "
                          "0.000000 to 10.000000 s: the two streams do not "
                          "overlap"));
  }
}

// Two topics of one recording count their times from their own first
// stamps: the origins put them on one clock.
TEST(MergeTwoStreams, TheRecordingsClockOriginsAreAddedBeforeComparing) {
  Recording rec = StreamAt(100.0, 0.0, 3.0, false);
  Recording gyro = StreamAt(200.0, 0.0, 2.5, true);
  rec.time_origin_ns = 1'700'000'000'000'000'000;
  gyro.time_origin_ns = rec.time_origin_ns + 500'000'000;  // starts 0.5 s later
  const StreamMerge m = MergeGyroLog(rec, gyro, GyroUnits::kRadps);
  EXPECT_NEAR(m.gyro_first_s, 0.5, 1e-9);
  EXPECT_NEAR(m.gyro_last_s, 3.0, 1e-9);
  EXPECT_EQ(m.rows_dropped_before, 50u);
  // The turn, 1 to 1.8 s on the gyroscope's clock, is 1.5 to 2.3 s on the
  // accelerometer's: the row at 1.9 s has the gyroscope's rate at 1.4 s.
  const auto it = std::lower_bound(rec.time_s.begin(), rec.time_s.end(), 1.9 - 1e-9);
  const auto i = static_cast<std::size_t>(it - rec.time_s.begin());
  EXPECT_NEAR(rec.gyro_radps[i].z(), TurnRate(1.4), 1e-3);
}

TEST(MergeTwoStreams, TheSameSamplesAreTakenRowByRow) {
  Recording rec = StreamAt(100.0, 0.0, 2.0, false);
  const Recording gyro = StreamAt(100.0, 0.0, 2.0, true);
  const StreamMerge m = MergeGyroLog(rec, gyro, GyroUnits::kRadps);
  EXPECT_FALSE(m.resampled);
  EXPECT_TRUE(rec.gyro_samples.empty());
  for (std::size_t i = 0; i < rec.size(); ++i) {
    ASSERT_EQ(rec.gyro_radps[i].z(), gyro.accel[i].z());
  }
}

}  // namespace
}  // namespace mpcal
