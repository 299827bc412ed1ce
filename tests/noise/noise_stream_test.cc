// NoiseStream: a record analysed as its rows arrive gives what the whole
// record held gives, whatever the split; its stillness verdict; the sample
// period and the gaps.
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include "mpcal/error.h"
#include "mpcal/noise.h"
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
  EXPECT_NEAR(r.sample_period_s, 0.01, 1e-12);
  EXPECT_FALSE(s.Stillness().has_value());
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
