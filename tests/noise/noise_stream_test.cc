// NoiseStream: a record analysed as its rows arrive gives what the whole
// record held gives, whatever the split; its stillness verdict; the sample
// period and the gaps.
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mpcal/error.h"
#include "mpcal/noise.h"
#include "mpcal/not_finite.h"
#include "mpcal/simulate.h"
#include "mpcal/simulate_noise.h"
#include "simulated_still.h"

namespace mpcal {
namespace {

Recording StillRecord(double minutes, double rate_hz, std::uint64_t seed) {
  NoiseSimulationOptions o = *NoisePreset("consumer");
  o.duration_s = minutes * 60.0;
  o.rate_hz = rate_hz;
  o.seed = seed;
  return SimulatedStill(o);
}

// The stream over `rec` in random pieces of up to `largest` rows.
NoiseStream& Feed(NoiseStream& s, const Recording& rec, std::size_t largest) {
  std::mt19937_64 rng(largest);
  std::uniform_int_distribution<std::size_t> size(1, largest);
  for (std::size_t i = 0; i < rec.size();) {
    const std::size_t e = std::min(rec.size(), i + size(rng));
    s.Add(rec, i, e);
    i = e;
  }
  return s;
}

void ExpectSameSensor(const SensorNoise& a, const SensorNoise& b) {
  for (int axis = 0; axis < 3; ++axis) {
    const AxisNoise& x = a.axes[axis];
    const AxisNoise& y = b.axes[axis];
    ASSERT_EQ(x.curve.size(), y.curve.size());
    for (std::size_t j = 0; j < x.curve.size(); ++j) {
      EXPECT_NEAR(x.curve[j].adev / y.curve[j].adev, 1.0, 1e-9) << axis << " " << j;
    }
    for (int t = 0; t < kNoiseTermCount; ++t) {
      EXPECT_EQ(x.terms[t].status, y.terms[t].status) << axis << " " << t;
      if (x.terms[t].value) {
        EXPECT_NEAR(*x.terms[t].value / *y.terms[t].value, 1.0, 1e-6);
      }
    }
    EXPECT_NEAR((a.mean_si - b.mean_si).norm(), 0.0, 1e-12);
  }
}

TEST(NoiseStream, PiecesGiveWhatTheHeldRecordGives) {
  const Recording rec = StillRecord(20.0, 100.0, 3);
  const NoiseSegment all{NoiseSegmentKind::kWholeRecord, 0, rec.size(), 1};
  const NoiseResult held = AnalyseNoise(rec, all, 1.0, NoiseOptions{});
  for (const std::size_t largest :
       {std::size_t{1}, std::size_t{977}, std::size_t{50000}}) {
    const DetectOptions detect;
    NoiseStream s(NoiseOptions{}, &detect, AccelUnits::kMps2);
    const NoiseResult r = Feed(s, rec, largest).Finish(1.0, all);
    EXPECT_EQ(s.rows(), rec.size());
    ASSERT_TRUE(s.Stillness().has_value());
    EXPECT_TRUE(s.Stillness()->still) << largest;
    EXPECT_DOUBLE_EQ(r.sample_period_s, held.sample_period_s);
    EXPECT_NEAR(r.sample_period_s, 0.01, 1e-12);
    EXPECT_EQ(r.gaps, 0u);
    EXPECT_EQ(r.samples, rec.size());
    ExpectSameSensor(r.accel_mps2, held.accel_mps2);
    ASSERT_TRUE(r.gyro_radps.has_value());
    ExpectSameSensor(*r.gyro_radps, *held.gyro_radps);
  }
}

TEST(NoiseStream, RefusesANonFiniteRowOfAView) {
  // Rows no log reader checked, read in place: a NaN would run through the
  // sums into every figure; it is refused, naming its column and row.
  const Recording rec = StillRecord(2.0, 100.0, 5);
  std::vector<Eigen::Vector3d> gyro = rec.gyro_radps;
  gyro[9000].y() = std::numeric_limits<double>::quiet_NaN();
  RecordingView view = rec;
  view.gyro_radps = gyro;
  const NoiseSegment all{NoiseSegmentKind::kWholeRecord, 0, rec.size(), 1};
  try {
    AnalyseNoise(view, all, 1.0, {});
    FAIL() << "no throw";
  } catch (const NotFiniteError& e) {
    EXPECT_EQ(e.column(), RowColumn::kGyro);
    EXPECT_EQ(e.row(), 9000u);
  }
  // The rows before it are analysed.
  const NoiseSegment before{NoiseSegmentKind::kLongestStill, 0, 9000, 1};
  EXPECT_EQ(AnalyseNoise(view, before, 1.0, {}).samples, 9000u);
}

TEST(NoiseStream, UnitsScaleTheAccelerometerOnly) {
  const Recording rec = StillRecord(5.0, 100.0, 4);
  const NoiseSegment all{NoiseSegmentKind::kWholeRecord, 0, rec.size(), 1};
  const NoiseResult si = AnalyseNoise(rec, all, 1.0, NoiseOptions{});
  const NoiseResult scaled = AnalyseNoise(rec, all, 2.0, NoiseOptions{});
  const auto n = [](const SensorNoise& s) {
    return *s.axes[0].term(NoiseTerm::kWhiteNoise).value;
  };
  EXPECT_NEAR(n(scaled.accel_mps2) / n(si.accel_mps2), 2.0, 1e-9);
  EXPECT_NEAR(n(*scaled.gyro_radps) / n(*si.gyro_radps), 1.0, 1e-12);
  EXPECT_NEAR(
      (scaled.accel_mps2.mean_si - 2.0 * si.accel_mps2.mean_si).norm(), 0.0, 1e-9);
}

TEST(NoiseStream, GapsAreStepsOverOneAndAHalfTheFirstSteps) {
  Recording rec = StillRecord(5.0, 100.0, 5);
  // Drop 3 single samples and one run of 10, all after the first 1,024
  // steps, and one before (counted once the reference is known).
  for (const std::size_t at : {20000u, 15000u, 8000u, 2000u, 500u}) {
    const std::size_t len = at == 8000u ? 10 : 1;
    rec.time_s.erase(rec.time_s.begin() + at, rec.time_s.begin() + at + len);
    rec.accel.erase(rec.accel.begin() + at, rec.accel.begin() + at + len);
    rec.gyro_radps.erase(rec.gyro_radps.begin() + at, rec.gyro_radps.begin() + at + len);
  }
  NoiseStream s(NoiseOptions{}, nullptr, AccelUnits::kMps2);
  const NoiseResult r =
      Feed(s, rec, 300).Finish(1.0, {NoiseSegmentKind::kWholeRecord, 0, rec.size(), 1});
  EXPECT_EQ(r.gaps, 5u);
  // The rate is the count over the span: 14 samples lost in 30,000 lower it.
  const double span_s = rec.time_s.back() - rec.time_s.front();
  EXPECT_NEAR(r.rate_hz, static_cast<double>(rec.size() - 1) / span_s, 1e-9);
  EXPECT_NEAR(r.rate_hz, 100.0 * (1.0 - 14.0 / 30000.0), 1e-3);
  EXPECT_FALSE(s.Stillness().has_value());
}

NoiseResult Analyse(const Recording& rec) {
  return AnalyseNoise(
      rec, {NoiseSegmentKind::kWholeRecord, 0, rec.size(), 1}, 1.0, NoiseOptions{});
}

// What Finish refuses with, for messages checked by the tests.
std::string Refusal(const Recording& rec) {
  try {
    Analyse(rec);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(NoiseStream, RateOfAMillisecondClockIsTheCountOverTheSpan) {
  // 300 Hz logged with a millisecond clock: steps of 3, 3, 4 ms. The median
  // step says 333 Hz, and every density would be √(333/300) off.
  NoiseSimulationOptions o = *NoisePreset("consumer");
  o.duration_s = 600.0;
  o.rate_hz = 300.0;
  o.seed = 11;
  Recording rec = SimulatedStill(o);
  for (double& t : rec.time_s) t = std::floor(t * 1000.0 + 1e-6) / 1000.0;
  const NoiseResult r = Analyse(rec);
  EXPECT_NEAR(r.rate_hz, 300.0, 0.01);  // the span is good to 1 ms in 600 s
  EXPECT_EQ(r.gaps, 0u);
  for (int axis = 0; axis < 3; ++axis) {
    const double truth = o.accel_mps2[axis].white_noise;
    // 180,000 samples measure N to a few tenths of a percent.
    EXPECT_NEAR(
        *r.accel_mps2.axes[axis].term(NoiseTerm::kWhiteNoise).value / truth, 1.0, 0.02)
        << axis;
  }
}

TEST(NoiseStream, TimesOfAHundredBillionSecondsGiveTheRate) {
  // A double resolves 1.5e-5 s at 1e11 s: single steps of 10 ms are off by
  // up to 0.15 %, the span of the record is not.
  Recording rec = StillRecord(5.0, 100.0, 12);
  for (double& t : rec.time_s) t += 1e11;
  EXPECT_NEAR(Analyse(rec).rate_hz, 100.0, 1e-3);
}

TEST(NoiseStream, ARateThatChangesIsRefused) {
  // 5 min at 100 Hz, then 5 min at 200 Hz.
  Recording rec = StillRecord(5.0, 100.0, 13);
  const Recording fast = StillRecord(5.0, 200.0, 14);
  const double end_s = rec.time_s.back();
  for (std::size_t i = 1; i < fast.size(); ++i) {
    rec.time_s.push_back(end_s + fast.time_s[i] - fast.time_s[0]);
    rec.accel.push_back(fast.accel[i]);
    rec.gyro_radps.push_back(fast.gyro_radps[i]);
  }
  const std::string why = Refusal(rec);
  EXPECT_THAT(why,
              testing::HasSubstr("the sample rate is not uniform: 200 Hz near t = "));
  EXPECT_THAT(why, testing::HasSubstr("100 Hz near t = "));
}

TEST(NoiseStream, ALargeGapIsRefusedAndASmallOneCounted) {
  Recording rec = StillRecord(5.0, 100.0, 15);
  const auto drop = [&](std::size_t at, std::size_t len) {
    rec.time_s.erase(rec.time_s.begin() + at, rec.time_s.begin() + at + len);
    rec.accel.erase(rec.accel.begin() + at, rec.accel.begin() + at + len);
    rec.gyro_radps.erase(rec.gyro_radps.begin() + at, rec.gyro_radps.begin() + at + len);
  };
  drop(10000, 20);  // 2 % of a block of 1,024 steps: counted
  EXPECT_EQ(Analyse(rec).gaps, 1u);
  drop(20000, 200);  // 20 %: refused, the gap named
  const std::string why = Refusal(rec);
  EXPECT_THAT(why, testing::HasSubstr("the sample rate is not uniform"));
  EXPECT_THAT(why, testing::HasSubstr("(no samples for 2.01 s after t = 200."));
}

TEST(NoiseStream, StepsThatAreNoTimeAreRefused) {
  Recording rec = StillRecord(0.5, 100.0, 16);
  for (std::size_t i = 0; i < rec.size(); ++i) rec.time_s[i] = 1e-300 * (i + 1.0);
  EXPECT_THAT(Refusal(rec), testing::HasSubstr("is not a sample rate"));
}

// The axes that produce no noise: a stuck one, a toggling one, one rounded
// far coarser than its noise; each named, with its figures.
TEST(NoiseStream, AxesThatProduceNoNoiseAreNamed) {
  Recording rec = StillRecord(5.0, 100.0, 17);
  const double q = 0.05;  // m/s²; the accelerometer's σ per sample is 0.015
  double mean_x = 0.0;
  for (const Eigen::Vector3d& a : rec.accel) mean_x += a.x() / rec.size();
  for (std::size_t i = 0; i < rec.size(); ++i) {
    // About a level of the quantiser: 0 and ±q, so three values or more.
    rec.accel[i].x() = std::round((rec.accel[i].x() - mean_x) / q) * q;
    rec.accel[i].z() = 9.81;
    rec.gyro_radps[i].y() = (i % 2 == 0) ? 0.001 : 0.002;
  }
  NoiseStream s(NoiseOptions{}, nullptr, AccelUnits::kMps2);
  s.Add(rec);
  const std::vector<AxisSignalFault> faults = s.Faults(1.0);
  ASSERT_EQ(faults.size(), 3u);
  EXPECT_FALSE(faults[0].gyroscope);
  EXPECT_EQ(faults[0].axis, 0);
  EXPECT_EQ(faults[0].fault, SignalFault::kBelowResolution);
  EXPECT_NEAR(faults[0].resolution_si, q, 1e-12);
  EXPECT_LT(faults[0].adev_tau0_si, q);
  EXPECT_EQ(faults[1].axis, 2);
  EXPECT_EQ(faults[1].fault, SignalFault::kStuck);
  EXPECT_DOUBLE_EQ(faults[1].value_si, 9.81);
  EXPECT_TRUE(faults[2].gyroscope);
  EXPECT_EQ(faults[2].axis, 1);
  EXPECT_EQ(faults[2].fault, SignalFault::kTwoValued);
  EXPECT_NEAR(faults[2].resolution_si, 0.001, 1e-12);
  const std::string why = Refusal(rec);
  EXPECT_THAT(why, testing::HasSubstr("accelerometer x: quantised beyond use"));
  EXPECT_THAT(why, testing::HasSubstr("accelerometer z: stuck at 9.81 m/s²"));
  EXPECT_THAT(why, testing::HasSubstr("gyroscope y: two values only"));
}

TEST(NoiseStream, NoiseRoundedFinerThanItselfIsNoise) {
  // Rounded to a quarter of its σ per sample, as a logger writing few digits
  // does: still the sensor's noise.
  Recording rec = StillRecord(5.0, 100.0, 18);
  for (Eigen::Vector3d& a : rec.accel) a = (a / 0.004).array().round() * 0.004;
  NoiseStream s(NoiseOptions{}, nullptr, AccelUnits::kMps2);
  s.Add(rec);
  EXPECT_TRUE(s.Faults(1.0).empty());
  EXPECT_NO_THROW(s.Finish(1.0, {NoiseSegmentKind::kWholeRecord, 0, rec.size(), 1}));
}

TEST(NoiseStream, AConstantLogIsRefused) {
  Recording rec = StillRecord(1.0, 100.0, 19);
  for (Eigen::Vector3d& a : rec.accel) a = Eigen::Vector3d(0.0, 0.0, 9.81);
  for (Eigen::Vector3d& g : rec.gyro_radps) g.setZero();
  const std::string why = Refusal(rec);
  for (const char* axis : {"accelerometer x: stuck at 0 m/s²",
                           "accelerometer y: stuck",
                           "accelerometer z: stuck",
                           "gyroscope x: stuck at 0 rad/s",
                           "gyroscope y: stuck",
                           "gyroscope z: stuck"}) {
    EXPECT_THAT(why, testing::HasSubstr(axis));
  }
}

TEST(NoiseStream, ACalibrationSessionMoved) {
  SimulateStaticOptions o;
  o.seed = 2;
  const SimulatedSession session = SimulateStatic(o);
  const DetectOptions detect;
  NoiseStream s(NoiseOptions{}, &detect, session.recording.units);
  Feed(s, session.recording, 4096);
  ASSERT_TRUE(s.Stillness().has_value());
  EXPECT_FALSE(s.Stillness()->still);
  EXPECT_EQ(s.Stillness()->reason, NotStillReason::kMoved);
}

TEST(NoiseStream, TooFewRowsAreRefused) {
  const Recording rec = StillRecord(0.1, 100.0, 6);
  NoiseStream s(NoiseOptions{}, nullptr, AccelUnits::kMps2);
  s.Add(rec, 0, 8);
  EXPECT_THROW(s.Finish(1.0, {}), Error);
  s.Add(rec, 8, 9);
  EXPECT_NO_THROW(s.Finish(1.0, {}));
}

}  // namespace
}  // namespace mpcal
