// The bias's random walk in the turns' weights (bias_walk.h): the bridge
// variance against quadrature, the walk density recovered from the rest
// biases, and a gyroscope whose bias wanders fitted with an honest variance
// factor (4.4 with the walk left out of the weights).
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "gyro/bias_walk.h"
#include "gyro/turn_problem.h"
#include "mpcal/detect.h"
#include "mpcal/gyro.h"
#include "mpcal/simulate.h"
#include "test_util.h"

namespace mpcal {
namespace {

using testing::kDeg;
// A quiet gyroscope whose bias wanders: over a 2 s turn between positions
// 7 s apart the walk leaves ~3e-4 rad, three times the white noise's part,
// and quiet accelerometer directions (~1e-4 rad), so the walk dominates.
constexpr double kWalkRadpsPerSqrtS = 1e-4;

SimulateStaticOptions WanderingBias(std::uint64_t seed) {
  SimulateStaticOptions o;
  o.device = FindPreset("colibri");
  o.device.range_mps2 = 0.0;
  o.device.resolution_mps2 = 0.0;
  o.device.noise_density_mps2_per_sqrt_hz = 0.001;
  o.device.gyro_bias_walk_radps_per_sqrt_s = kWalkRadpsPerSqrtS;
  o.gyro_noise_density_radps_per_sqrt_hz = 0.005 * kDeg;
  o.seed = seed;
  o.dwell_s = 5.0;
  o.gyro = true;
  // Without the hand's fast shake in the turns: sampled at 100 Hz, its
  // 3 degrees leave an integration error far above this quiet gyroscope's
  // noise (variance factor ~12 with no walk at all), which is not the
  // subject here.
  o.shake_rotation_deg = 0.0;
  return o;
}

TEST(GyroBiasWalk, BridgeVarianceMatchesQuadrature) {
  // Var ∫ B over [s0, s1] = ∬ (min(s, u) − s u / span) ds du, midpoint rule.
  const double pin_a = 3.0;
  const double pin_b = 23.0;
  const double s0 = 11.0;
  const double s1 = 13.5;
  constexpr int kPoints = 2000;
  const double h = (s1 - s0) / kPoints;
  double sum = 0.0;
  for (int i = 0; i < kPoints; ++i) {
    const double s = s0 + (i + 0.5) * h - pin_a;
    for (int j = 0; j < kPoints; ++j) {
      const double u = s0 + (j + 0.5) * h - pin_a;
      sum += (std::min(s, u) - s * u / (pin_b - pin_a)) * h * h;
    }
  }
  EXPECT_NEAR(internal::BridgeIntegralVariance(pin_a, pin_b, s0, s1), sum, 1e-6 * sum);
  // Nothing is left at the pins, and nothing outside them.
  EXPECT_DOUBLE_EQ(internal::BridgeIntegralVariance(pin_a, pin_b, 30.0, 40.0), 0.0);
  EXPECT_DOUBLE_EQ(internal::BridgeIntegralVariance(pin_a, pin_a, 3.0, 4.0), 0.0);
}

TEST(GyroBiasWalk, DensityRecoveredFromTheRestBiases) {
  // 25 changes × 3 axes per session: the estimate of the density² has a
  // relative standard deviation of about 0.2 (more with the white noise
  // subtracted); over four sessions about 0.1, so ±35 % is over 3σ.
  double sum = 0.0;
  constexpr int kSessions = 4;
  for (int s = 0; s < kSessions; ++s) {
    const SimulatedSession session = SimulateStatic(WanderingBias(100 + s));
    const DetectResult det = DetectStatic(session.recording, {});
    const internal::TurnProblem problem = internal::BuildTurnProblem(session.recording,
                                                                     det.intervals,
                                                                     session.truth,
                                                                     1.0,
                                                                     GSensitivity::kOff,
                                                                     0.0,
                                                                     0.0);
    sum += internal::EstimateBiasWalk(
        problem, det.intervals, session.recording, session.truth);
  }
  const double truth = kWalkRadpsPerSqrtS * kWalkRadpsPerSqrtS;
  EXPECT_NEAR(sum / kSessions, truth, 0.35 * truth);
}

TEST(GyroBiasWalk, VarianceFactorHonestWhenTheBiasWanders) {
  // With the walk in the weights χ²/dof is 1 ± 0.22 per session (41 dof);
  // the mean of eight sessions within ±0.25 is over 3σ. Without it, 4.4.
  double sum = 0.0;
  constexpr int kSessions = 8;
  for (int s = 0; s < kSessions; ++s) {
    const SimulatedSession session = SimulateStatic(WanderingBias(200 + s));
    const DetectResult det = DetectStatic(session.recording, {});
    const GyroResult r =
        CalibrateGyroscope(session.recording, det.intervals, session.truth, {});
    ASSERT_TRUE(r.converged()) << "seed " << 200 + s;
    sum += r.calibration.fit->variance_factor;
  }
  EXPECT_NEAR(sum / kSessions, 1.0, 0.25);
}

}  // namespace
}  // namespace mpcal
