// `calibrate` reports each axis's white noise from the scatter within its
// static positions; on the same session it agrees with the Allan analysis
// of the longest still part.
#include <cmath>

#include <gtest/gtest.h>

#include "mpcal/calibrate.h"
#include "mpcal/noise.h"
#include "mpcal/simulate.h"

namespace mpcal {
namespace {

TEST(WhiteNoiseFromPositions, AgreesWithTheAllanAnalysisOfTheSameSession) {
  SimulateStaticOptions o;
  o.device = FindPreset("mti-g");
  o.seed = 5;
  o.initial_rest_s = 120.0;  // a long still part for the Allan analysis
  const SimulatedSession s = SimulateStatic(o);
  const CalibrateResult cal = CalibrateRecording(s.recording, CalibrateOptions{});
  const std::optional<Eigen::Vector3d> n =
      WhiteNoiseFromPositions(cal.calibration.positions);
  ASSERT_TRUE(n.has_value());

  Recording rec = s.recording;
  const std::optional<NoiseSegment> seg = ChooseNoiseSegment(rec, cal.detection);
  ASSERT_TRUE(seg.has_value());
  EXPECT_EQ(seg->kind, NoiseSegmentKind::kLongestStill);
  const NoiseResult r = AnalyseNoise(std::move(rec), *seg, 1.0, NoiseOptions{});
  for (int axis = 0; axis < 3; ++axis) {
    const TermEstimate& w = r.accel_mps2.axes[axis].term(NoiseTerm::kWhiteNoise);
    ASSERT_TRUE(w.value.has_value());
    // Both estimate the same density from ~10⁵ samples (σ ≈ 0.3 %); the
    // quantisation of the simulated readings adds the same to both.
    EXPECT_NEAR((*n)[axis] / *w.value, 1.0, 0.03) << axis;
    // The simulator's density is one-sided (σ = ρ√(f/2)): N = σ/√f = ρ/√2.
    EXPECT_NEAR(*w.value / (s.noise_std_mps2[axis] / std::sqrt(s.rate_hz)), 1.0, 0.03);
  }
}

TEST(WhiteNoiseFromPositions, NoneWithoutUsablePositions) {
  EXPECT_FALSE(WhiteNoiseFromPositions({}).has_value());
  PositionSummary p;
  p.samples = 1;
  EXPECT_FALSE(WhiteNoiseFromPositions({p}).has_value());
}

}  // namespace
}  // namespace mpcal
