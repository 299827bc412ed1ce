// The Allan deviation itself: the sums against the definition, the estimator on
// white noise and on a random walk against their closed forms, the EDF and
// the χ² quantiles behind the confidence intervals.
#include <algorithm>
#include <cmath>
#include <cstdint>
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

// The sums of `v` (added in pieces of `piece` samples; 0: at once) and
// their analysis, as AnalyseNoise runs them for one sensor.
AllanSums SumsOf(const std::vector<Eigen::Vector3d>& v, std::size_t piece = 0) {
  AllanSums s(AllanOptions{});
  if (piece == 0) piece = v.size();
  for (std::size_t i = 0; i < v.size(); i += piece) {
    s.Add(v.data() + i, std::min(piece, v.size() - i));
  }
  return s;
}

SensorNoise Analyse(const std::vector<Eigen::Vector3d>& v, double period_s) {
  return AnalyseSensorNoise(SumsOf(v), 1.0, period_s, NoiseOptions{});
}

// σ² at m with starts every `stride`, straight from the definition, θ in
// long double.
long double DirectAvar(const std::vector<Eigen::Vector3d>& y,
                       int axis,
                       std::int64_t m,
                       std::int64_t stride) {
  std::vector<long double> theta(y.size() + 1, 0.0L);
  for (std::size_t i = 0; i < y.size(); ++i) theta[i + 1] = theta[i] + y[i][axis];
  const auto n = static_cast<std::int64_t>(y.size());
  long double sum = 0.0L;
  std::int64_t terms = 0;
  for (std::int64_t k = 0; k + 2 * m <= n; k += stride, ++terms) {
    const long double v = theta[k + 2 * m] - 2.0L * theta[k + m] + theta[k];
    sum += v * v;
  }
  return sum / (2.0L * m * m * terms);
}

TEST(AllanSums, EqualsTheDefinitionWhateverTheSplit) {
  // 20,000 samples: cluster sizes to 5,000, the far ones (stride 64 and
  // more, from the kept sums) included.
  const std::vector<Eigen::Vector3d> v = WhiteNoise(20000, 1.0, 3);
  const auto whole = SumsOf(v).Curves(2.0, 0.01);
  ASSERT_GT(whole[0].back().stride, AllanSums::kFarStride - 1);
  for (int axis = 0; axis < 3; ++axis) {
    for (const AllanPoint& p : whole[axis]) {
      const double direct =
          static_cast<double>(4.0L * DirectAvar(v, axis, p.m, p.stride));
      EXPECT_NEAR(p.avar / direct, 1.0, 1e-9) << axis << " m " << p.m;
      EXPECT_DOUBLE_EQ(p.tau_s, 0.01 * static_cast<double>(p.m));
    }
  }
  std::mt19937_64 rng(5);
  for (const std::size_t piece : {std::size_t{1}, std::size_t{7}, std::size_t{9000}}) {
    const auto split = SumsOf(v, piece).Curves(2.0, 0.01);
    for (int axis = 0; axis < 3; ++axis) {
      ASSERT_EQ(split[axis].size(), whole[axis].size());
      for (std::size_t j = 0; j < whole[axis].size(); ++j) {
        EXPECT_NEAR(split[axis][j].avar / whole[axis][j].avar, 1.0, 1e-12) << piece;
        EXPECT_EQ(split[axis][j].terms, whole[axis][j].terms);
      }
    }
  }
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& x : v) mean += x;
  EXPECT_NEAR((SumsOf(v, 7).Mean() - mean / 20000.0).norm(), 0.0, 1e-12);
}

TEST(AllanSums, WhiteNoiseFollowsNOverRootTauWithinItsInterval) {
  const double rate_hz = 100.0, n_density = 0.02;  // u/√Hz
  const std::size_t n = 400000;
  std::vector<Eigen::Vector3d> v = WhiteNoise(n, n_density * std::sqrt(rate_hz), 11);
  const SensorNoise r = Analyse(v, 1 / rate_hz);
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

TEST(AllanSums, RandomWalkFollowsKRootTauOverThree) {
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
    const SensorNoise r = Analyse(v, 1 / rate_hz);
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

TEST(AllanSums, RefusesTooFewSamples) {
  const std::vector<Eigen::Vector3d> v = WhiteNoise(7, 1.0, 1);
  EXPECT_THROW(SumsOf(v).Curves(1.0, 0.01), Error);
  EXPECT_EQ(SumsOf(WhiteNoise(8, 1.0, 1)).Curves(1.0, 0.01)[0].size(), 2u);  // m = 1, 2
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
