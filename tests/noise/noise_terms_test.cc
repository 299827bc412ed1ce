// Noise terms from simulated still records with known N, B and K: recovered
// within their intervals where the curve shows them, and where it does not,
// "not measured" with the record length that would show them.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "mpcal/noise.h"
#include "mpcal/simulate_noise.h"
#include "simulated_still.h"

namespace mpcal {
namespace {

struct Simulated {
  NoiseResult result;
  NoiseSimulationOptions truth;
};

Simulated Simulate(const std::string& preset,
                   double hours,
                   double rate_hz,
                   std::uint64_t seed) {
  NoiseSimulationOptions o = *NoisePreset(preset);
  o.duration_s = hours * 3600.0;
  o.rate_hz = rate_hz;
  o.seed = seed;
  Recording rec = SimulatedStill(o);
  NoiseSegment all;
  all.end = rec.size();
  return {AnalyseNoise(std::move(rec), all, 1.0, NoiseOptions{}), o};
}

TEST(NoiseTerms, ConsumerTwoHoursRecoversNBAndK) {
  const Simulated s = Simulate("consumer", 2.0, 50.0, 7);
  EXPECT_NEAR(s.result.rate_hz, 50.0, 1e-9);
  EXPECT_EQ(s.result.gaps, 0u);
  ASSERT_TRUE(s.result.gyro_radps.has_value());
  int walks_measured = 0;
  for (int sensor = 0; sensor < 2; ++sensor) {
    const SensorNoise& sn = sensor == 0 ? s.result.accel_mps2 : *s.result.gyro_radps;
    const auto& truth = sensor == 0 ? s.truth.accel_mps2 : s.truth.gyro_radps;
    for (int axis = 0; axis < 3; ++axis) {
      const AxisNoise& a = sn.axes[axis];
      const TermEstimate& n = a.term(NoiseTerm::kWhiteNoise);
      const TermEstimate& k = a.term(NoiseTerm::kRandomWalk);
      const TermEstimate& b = a.term(NoiseTerm::kBiasInstability);
      ASSERT_EQ(n.status, TermStatus::kMeasured);
      EXPECT_NEAR(*n.value / truth[axis].white_noise, 1.0, 0.03) << sensor << axis;
      if (k.value) {
        ++walks_measured;
        EXPECT_NEAR(*k.value / truth[axis].random_walk, 1.0, 0.6) << sensor << axis;
      } else {
        EXPECT_GE(k.upper_bound, 0.8 * truth[axis].random_walk) << sensor << axis;
        EXPECT_TRUE(k.record_needed_s.has_value());
      }
      // B shows only where it rises above N and K (accelerometer x here).
      if (sensor == 0 && axis == 0) {
        ASSERT_EQ(b.status, TermStatus::kMeasured);
      }
      if (b.value) {
        EXPECT_NEAR(*b.value / truth[axis].bias_instability, 1.0, 0.35) << sensor << axis;
      } else {
        EXPECT_GE(b.upper_bound, truth[axis].bias_instability) << sensor << axis;
      }
    }
  }
  EXPECT_GE(walks_measured, 2);  // the accelerometer's; the gyroscope's show later
}

TEST(NoiseTerms, TenMinutesCannotMeasureTheRandomWalkAndSaysHowLongToRecord) {
  const Simulated s = Simulate("consumer", 10.0 / 60.0, 100.0, 3);
  for (const SensorNoise* sn : {&s.result.accel_mps2, &*s.result.gyro_radps}) {
    for (const AxisNoise& a : sn->axes) {
      const TermEstimate& k = a.term(NoiseTerm::kRandomWalk);
      EXPECT_EQ(k.status, TermStatus::kNotSeen);
      EXPECT_FALSE(k.value.has_value());  // never a number that was not measured
      EXPECT_GT(k.upper_bound, 0.0);
      ASSERT_TRUE(k.record_needed_s.has_value());
      // Longer than this record, and longer again for a smaller walk (the
      // +½ line must rise above the flat floor: about 4x for half of it).
      EXPECT_GT(*k.record_needed_s, 1.8 * 600.0);
      ASSERT_TRUE(k.record_needed_half_s.has_value());
      // Records are tried an eighth of an octave apart: at least 8 steps on.
      EXPECT_GE(*k.record_needed_half_s, 2.0 * *k.record_needed_s * (1.0 - 1e-9));
      EXPECT_EQ(a.term(NoiseTerm::kWhiteNoise).status, TermStatus::kMeasured);
    }
  }
}

TEST(NoiseTerms, FlickerApproximationIsFlatAtPoint664B) {
  NoiseSimulationOptions o;
  o.duration_s = 4 * 3600.0;
  o.rate_hz = 10.0;
  // White noise over the flicker's roll-off below 10 flicker_min_tau_s.
  for (auto& a : o.accel_mps2) a = {1e-3, 1e-3, 0.0};
  for (auto& a : o.gyro_radps) a = {1e-6, 0.0, 0.0};
  NoiseGenerator gen(o);
  std::vector<Eigen::Vector3d> accel;
  double t;
  Eigen::Vector3d a, g;
  while (gen.Next(&t, &a, &g)) accel.push_back(a);
  AllanSums sums(AllanOptions{});
  sums.Add(accel.data(), accel.size());
  const SensorNoise r = AnalyseSensorNoise(sums, 1.0, 0.1, NoiseOptions{});
  for (const AxisNoise& ax : r.axes) {
    int inside = 0, count = 0;
    for (const AllanPoint& p : ax.curve) {
      const double truth = std::sqrt(0.4413 * 1e-6 + 1e-6 / p.tau_s);
      if (p.tau_s >= 10.0) {  // where the flicker is flat
        ++count;
        inside += p.adev_lo <= truth && truth <= p.adev_hi;
      }
      if (p.tau_s < 0.02 * o.duration_s) {
        EXPECT_NEAR(p.adev / truth, 1.0, 0.1) << p.tau_s;
      }
    }
    EXPECT_GE(inside, 0.6 * count);  // neighbouring points are correlated
    ASSERT_TRUE(ax.term(NoiseTerm::kBiasInstability).value.has_value());
    EXPECT_NEAR(*ax.term(NoiseTerm::kBiasInstability).value / 1e-3, 1.0, 0.1);
  }
}

}  // namespace
}  // namespace mpcal
