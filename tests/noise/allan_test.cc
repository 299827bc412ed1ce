// The Allan deviation itself: cumulative sums in place, the estimator on
// white noise and on a random walk against their closed forms, the EDF and
// the χ² quantiles behind the confidence intervals.
#include <cmath>
#include <random>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mpcal/error.h"
#include "mpcal/noise.h"

namespace mpcal {
namespace {

std::vector<Eigen::Vector3d> WhiteNoise(std::size_t n, double sigma, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, sigma);
  std::vector<Eigen::Vector3d> v(n);
  for (auto& x : v) x = Eigen::Vector3d(normal(rng), normal(rng), 9.8 + normal(rng));
  return v;
}

TEST(ChiSquareQuantile, MatchesTables) {
  EXPECT_NEAR(ChiSquareQuantile(0.975, 1.0), 5.0239, 1e-3);
  EXPECT_NEAR(ChiSquareQuantile(0.025, 10.0), 3.2470, 1e-3);
  EXPECT_NEAR(ChiSquareQuantile(0.5, 2.0), 1.3863, 1e-3);
  // Non-integer ν: between its neighbours, and P(χ²₂ ≤ x) = 1 − e^(−x/2).
  EXPECT_GT(ChiSquareQuantile(0.95, 2.5), 5.9915);
  EXPECT_LT(ChiSquareQuantile(0.95, 2.5), 7.8147);
  EXPECT_NEAR(ChiSquareQuantile(0.3, 2.0), -2.0 * std::log(0.7), 1e-9);
  // Wilson-Hilferty branch against the exact one at the switch.
  EXPECT_NEAR(
      ChiSquareQuantile(0.05, 2001.0) / ChiSquareQuantile(0.05, 1999.0), 1.0, 2e-3);
}

TEST(OverlappingAllanEdf, WhiteNoiseIsAboutThreeHalvesOfTheClusters) {
  // Riley (NIST SP 1065) Table 5: white FM, N = 1025, m = 16: about 92.
  EXPECT_NEAR(OverlappingAllanEdf(1025, 16, NoiseTerm::kWhiteNoise), 94.0, 3.0);
  EXPECT_NEAR(OverlappingAllanEdf(1e6, 250000, NoiseTerm::kRandomWalk), 2.0, 0.1);
}

TEST(CumulativeSums3, InPlaceEqualsTheDirectSumOfTheSegment) {
  std::vector<Eigen::Vector3d> v = WhiteNoise(1000, 1.0, 3);
  const std::vector<Eigen::Vector3d> copy = v;
  const CumulativeSums3 s =
      CumulativeSums3::FromSamples(std::move(v), 100, 600, 2.0, 0.01);
  ASSERT_EQ(s.size(), 501u);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int i = 100; i < 600; ++i) mean += copy[i];
  mean /= 500.0;
  EXPECT_NEAR((s.mean_si() - 2.0 * mean).norm(), 0.0, 1e-12);
  Eigen::Vector3d run = Eigen::Vector3d::Zero();
  for (int k = 0; k <= 500; ++k) {
    EXPECT_NEAR((s.theta()[k] - 2.0 * run).norm(), 0.0, 1e-9) << k;
    if (k < 500) run += copy[100 + k] - mean;
  }
}

TEST(CumulativeSums3, WholeVectorDropsTheLastSampleRatherThanGrow) {
  std::vector<Eigen::Vector3d> v = WhiteNoise(100, 1.0, 4);
  const CumulativeSums3 s = CumulativeSums3::FromSamples(std::move(v), 0, 100, 1.0, 0.01);
  EXPECT_EQ(s.size(), 100u);
  EXPECT_NEAR(s.theta().back().norm(), 0.0, 1e-9);  // the mean is removed
}

TEST(OverlappingAllan, WhiteNoiseFollowsNOverRootTauWithinItsInterval) {
  const double rate_hz = 100.0, n_density = 0.02;  // u/√Hz
  const std::size_t n = 400000;
  std::vector<Eigen::Vector3d> v = WhiteNoise(n, n_density * std::sqrt(rate_hz), 11);
  const CumulativeSums3 s =
      CumulativeSums3::FromSamples(std::move(v), 0, n, 1.0, 1 / rate_hz);
  const SensorNoise r = AnalyseSensorNoise(s, NoiseOptions{});
  for (int axis = 0; axis < 3; ++axis) {
    const AxisNoise& a = r.axes[axis];
    ASSERT_GT(a.curve.size(), 40u);
    int inside = 0;
    for (const AllanPoint& p : a.curve) {
      const double truth = n_density / std::sqrt(p.tau_s);
      inside += truth >= p.adev_lo && truth <= p.adev_hi;
      EXPECT_LE(p.tau_s, 0.25 * n / rate_hz + 1e-9);
    }
    // 95 % intervals; neighbouring points are correlated, so allow some.
    EXPECT_GE(inside, static_cast<int>(0.85 * a.curve.size())) << axis;
    const TermEstimate& w = a.term(NoiseTerm::kWhiteNoise);
    ASSERT_EQ(w.status, TermStatus::kMeasured);
    // σ(N)/N ≈ 1/√(2·1.5·n) ≈ 0.1 %: 1 % is 10σ.
    EXPECT_NEAR(*w.value / n_density, 1.0, 0.01) << axis;
    EXPECT_LE(w.lo, n_density);
    EXPECT_GE(w.hi, n_density);
    EXPECT_NE(a.term(NoiseTerm::kRandomWalk).status, TermStatus::kMeasured);
    EXPECT_NE(a.term(NoiseTerm::kBiasInstability).status, TermStatus::kMeasured);
  }
}

TEST(OverlappingAllan, RandomWalkFollowsKRootTauOverThree) {
  const double rate_hz = 50.0, k_density = 1e-3;  // u/s/√Hz
  const std::size_t n = 200000;
  int covered = 0, trials = 0;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> normal(0.0, k_density / std::sqrt(rate_hz));
    std::vector<Eigen::Vector3d> v(n);
    Eigen::Vector3d walk(0.1, 0.2, 0.3);
    for (auto& x : v) {
      x = walk;
      walk += Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
    }
    const CumulativeSums3 s =
        CumulativeSums3::FromSamples(std::move(v), 0, n, 1.0, 1 / rate_hz);
    const SensorNoise r = AnalyseSensorNoise(s, NoiseOptions{});
    for (const AxisNoise& a : r.axes) {
      // The curve: the closed form of a sampled random walk (the continuous
      // K²τ/3 plus K²/(6 f_s² τ) from the sampling) within the intervals.
      int inside = 0;
      for (const AllanPoint& p : a.curve) {
        const double truth =
            k_density *
            std::sqrt(p.tau_s / 3.0 + 1.0 / (6.0 * rate_hz * rate_hz * p.tau_s));
        inside += p.adev_lo <= truth && truth <= p.adev_hi;
      }
      // Neighbouring points share most of their data: a whole stretch of
      // the curve can sit outside together, so not 95 % of them.
      EXPECT_GE(inside, static_cast<int>(0.6 * a.curve.size()));
      const TermEstimate& k = a.term(NoiseTerm::kRandomWalk);
      ASSERT_EQ(k.status, TermStatus::kMeasured);
      ++trials;
      covered += k.lo <= k_density && k_density <= k.hi;

      EXPECT_NEAR(*k.value / k_density, 1.0, 0.5);
    }
  }
  // 95 % intervals over 30 axes: at least 24 is 4σ of a binomial below 28.5.
  EXPECT_GE(covered, 24) << covered << " of " << trials;
}

TEST(OverlappingAllan, RefusesTooFewSamples) {
  std::vector<Eigen::Vector3d> v = WhiteNoise(6, 1.0, 1);
  const CumulativeSums3 s = CumulativeSums3::FromSamples(std::move(v), 0, 6, 1.0, 0.01);
  EXPECT_THROW(OverlappingAllan(s, AllanOptions{}), Error);
}

TEST(AllanOptions, DefaultsAreValidAndBadFieldsNamed) {
  EXPECT_EQ(NoiseOptions{}.Validate(), "");
  AllanOptions o;
  o.max_tau_fraction = 0.9;
  EXPECT_THAT(o.Validate(), testing::HasSubstr("max_tau_fraction"));
  NoiseOptions n;
  n.dominance = 1.5;
  EXPECT_THAT(n.Validate(), testing::HasSubstr("dominance"));
}

}  // namespace
}  // namespace mpcal
