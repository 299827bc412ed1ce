// The statistics of heavy-tailed position residuals (README, "Honest 1σ on
// real recordings"): when a scatter component is read from the residuals,
// and when a position is an outlier.
#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "mpcal/error.h"
#include "mpcal/solve.h"
#include "solve/weights.h"
#include "solve_fixture.h"
#include "synthetic_positions.h"

namespace mpcal {
namespace {

using testing::ConsumerGrade;
using testing::CubeDirections;
using testing::MakeSession;
using testing::Tilted;

using testing::kNoise;
using testing::kSamples;

TEST(ChiSquare1MedianQuantile, IsTheChiSquareQuantileForOneValue) {
  // One value: its median is itself; χ²₁ exceeds 6.6349 with probability 1 %.
  EXPECT_NEAR(internal::ChiSquare1MedianQuantile(1, 0.01), 6.6349, 1e-3);
  EXPECT_NEAR(internal::ChiSquare1MedianQuantile(1, 0.05), 3.8415, 1e-3);
}

TEST(ChiSquare1MedianQuantile, MatchesTheSampledMedians) {
  // 20000 medians of 19 χ²₁ values: 1 % of them above the quantile.
  std::mt19937_64 rng(3);
  std::normal_distribution<double> n(0.0, 1.0);
  const double q = internal::ChiSquare1MedianQuantile(19, 0.01);
  int above = 0;
  constexpr int kDraws = 20000;
  for (int i = 0; i < kDraws; ++i) {
    std::vector<double> v(19);
    for (double& x : v) x = std::pow(n(rng), 2);
    std::nth_element(v.begin(), v.begin() + 9, v.end());
    above += v[9] > q;
  }
  // Binomial(20000, 0.01): 200 ± 14.
  EXPECT_NEAR(above, 200, 45);
}

TEST(PositionScatterVariance, ReadFromNineRedundantPositionsWhenTheEvidenceIsStrong) {
  // 18 positions for 9 parameters, every residual five times its σ: the
  // Xsens recording's first half. The old rule needed 10 redundant ones.
  const std::vector<double> residuals(18, 5e-3), sigmas(18, 1e-3), leverages(18, 0.5);
  const double tau2 = internal::PositionScatterVariance(residuals, sigmas, leverages);
  ASSERT_GT(tau2, 0.0);
  // Equal residuals: matching their mean r²/((σ² + τ²)(1 − h)) to 1 gives
  // the smaller τ² than matching their median to χ²₁'s (0.455).
  EXPECT_NEAR(25e-6 / ((1e-6 + tau2) * 0.5), 1.0, 1e-6);
}

TEST(PositionScatterVariance, NoLargerThanTheMeanOfTheStandardisedSquaresSays) {
  // Ten standardised squares at 2 and eight at 0: the median (2) passes the
  // test, but the mean (1.11) says the scatter is small; the median alone
  // would read τ² = 3.4 σ².
  std::vector<double> residuals;
  for (int k = 0; k < 18; ++k) residuals.push_back(k < 10 ? std::sqrt(2.0) * 1e-3 : 0.0);
  const std::vector<double> sigmas(18, 1e-3), leverages(18, 0.0);
  const double tau2 = internal::PositionScatterVariance(residuals, sigmas, leverages);
  EXPECT_NEAR(tau2, (20.0 / 18.0 - 1.0) * 1e-6, 1e-9);
}

TEST(PositionScatterVariance, NotFromFewerThanFiveRedundantPositions) {
  const std::vector<double> residuals(13, 5e-3), sigmas(13, 1e-3),
      leverages(13, 9.0 / 13);
  EXPECT_EQ(internal::PositionScatterVariance(residuals, sigmas, leverages), 0.0);
}

TEST(PositionScatterVariance, NotWhenTheMedianIsWithinChance) {
  // Ten standardised squares at 1, eight at 2500: a median of 1 is within
  // what 18 values of χ²₁ give once in 100 (1.46), whatever the tail.
  std::vector<double> residuals;
  for (int k = 0; k < 18; ++k) residuals.push_back(k < 10 ? 1e-3 : 50e-3);
  const std::vector<double> sigmas(18, 1e-3), leverages(18, 0.0);
  EXPECT_EQ(internal::PositionScatterVariance(residuals, sigmas, leverages), 0.0);
}

// White noise at the stated level: the scatter test at 1 % fires in about 1
// session in 100, at any number of positions.
TEST(Solve, WhiteNoiseSessionsRarelyShowAScatter) {
  std::mt19937_64 rng(21);
  const auto cube = CubeDirections();
  int with_scatter = 0;
  constexpr int kSessions = 300;
  SolveOptions options;
  options.cross_validate = false;
  for (int s = 0; s < kSessions; ++s) {
    std::vector<Eigen::Vector3d> directions = cube;
    std::shuffle(directions.begin(), directions.end(), rng);
    directions.resize(14 + static_cast<std::size_t>(s) % 13);
    const auto session =
        MakeSession(ConsumerGrade(), Tilted(directions, 0.1, rng), kNoise, kSamples, rng);
    try {
      with_scatter += Solve(session.positions, options).position_scatter_mps2 > 0.0;
    } catch (const Error&) {
      // A random subset of the cube may leave a parameter undetermined.
    }
  }
  // Binomial(300, 0.01): 3, and 9 or more with probability below 0.1 %.
  EXPECT_LE(with_scatter, 8);
}

// Means that scatter three times more than the noise of their samples says
// (hand tremor): with 18 positions the scatter is now read from the
// residuals, and the 1σ follows the real scatter rather than the noise.
TEST(Solve, ReadsTheScatterOfEighteenPositions) {
  std::mt19937_64 rng(22);
  std::vector<Eigen::Vector3d> directions = CubeDirections();
  directions.resize(18);
  constexpr double kExcess = 3.0;
  auto session = MakeSession(
      ConsumerGrade(), Tilted(directions, 0.1, rng), kExcess * kNoise, kSamples, rng);
  for (auto& p : session.positions) p.sample_std_mps2 /= kExcess;
  const SolveResult r = Solve(session.positions, SolveOptions{});
  ASSERT_TRUE(r.converged()) << r.message;
  EXPECT_GT(r.position_scatter_mps2, 0.0);
}

// A position far beyond its own noise level is excluded even where the
// others scatter widely (a large robust scale, and too few positions to read
// a scatter component from): the robust scale must not shelter it.
TEST(Solve, ExcludesAPositionTenTimesItsOwnNoiseWhateverTheScatter) {
  std::mt19937_64 rng(23);
  std::vector<Eigen::Vector3d> directions = CubeDirections();
  directions.resize(13);
  constexpr double kExcess = 3.0;
  auto session = MakeSession(
      ConsumerGrade(), Tilted(directions, 0.1, rng), kExcess * kNoise, kSamples, rng);
  for (auto& p : session.positions) p.sample_std_mps2 /= kExcess;
  // 30 times the noise of the mean along the reading.
  constexpr std::size_t kBumped = 12;
  const double sigma_mean = kNoise.norm() / std::sqrt(3.0 * kSamples);
  session.positions[kBumped].mean_mps2 +=
      30.0 * sigma_mean * session.positions[kBumped].mean_mps2.normalized();
  const SolveResult r = Solve(session.positions, SolveOptions{});
  ASSERT_TRUE(r.converged()) << r.message;
  EXPECT_EQ(r.position_scatter_mps2, 0.0);
  EXPECT_FALSE(r.used[kBumped]);
  EXPECT_EQ(std::count(r.used.begin(), r.used.end(), false), 1);
}

}  // namespace
}  // namespace mpcal
