// The rules inside Solve's named steps (src/solve/solve_steps.h), each on
// plain numbers: which position is the outlier, the reference time of a
// drifting bias, the F test of the drift, the plausible region and the
// covariance scale.
#include <cmath>

#include <gtest/gtest.h>

#include "mpcal/solve.h"
#include "solve/solve_steps.h"

namespace mpcal::internal {
namespace {

StandardisedResiduals Residuals(std::vector<double> total, std::vector<double> own) {
  return StandardisedResiduals{std::move(total), std::move(own)};
}

TEST(WorstOutlier, NoneWhenEveryResidualIsWithinTheThreshold) {
  const auto z = Residuals({0.5, -1.2, 2.0, -0.3, 4.9}, {0.5, -1.2, 2.0, -0.3, 4.9});
  EXPECT_FALSE(WorstOutlier(z, 5.0).has_value());
}

TEST(WorstOutlier, PicksTheWorstBeyondTheThreshold) {
  const auto z = Residuals({0.5, -6.0, 1.0, -0.3, 8.0}, {0.5, -6.0, 1.0, -0.3, 8.0});
  ASSERT_TRUE(WorstOutlier(z, 5.0).has_value());
  EXPECT_EQ(*WorstOutlier(z, 5.0), 4u);
}

TEST(WorstOutlier, ARobustScaleOfHeavyTailsSheltersAModeratePosition) {
  // The rest scatter at ~3σ: 1.4826 × median |z| ≈ 4.4, so 12 is within
  // 5 × 4.4 and stays, as long as it is within 10 times its own noise.
  const auto z =
      Residuals({3.0, -3.0, 2.8, -3.2, 3.1, 12.0}, {3.0, -3.0, 2.8, -3.2, 3.1, 9.0});
  EXPECT_FALSE(WorstOutlier(z, 5.0).has_value());
}

TEST(WorstOutlier, TenTimesItsOwnNoiseIsNotSheltered) {
  // The same, but the position is 11 times its own noise level: judged
  // against the threshold alone, whatever the scatter of the rest.
  const auto z =
      Residuals({3.0, -3.0, 2.8, -3.2, 3.1, 12.0}, {3.0, -3.0, 2.8, -3.2, 3.1, 11.0});
  ASSERT_TRUE(WorstOutlier(z, 5.0).has_value());
  EXPECT_EQ(*WorstOutlier(z, 5.0), 5u);
}

TEST(BiasReferenceTime, IsTheMeanMiddleOfTheUsedPositions) {
  std::vector<PositionObservation> p(3);
  p[0].start_s = 0.0;
  p[0].end_s = 10.0;  // middle 5
  p[1].start_s = 20.0;
  p[1].end_s = 30.0;  // middle 25, excluded
  p[2].start_s = 40.0;
  p[2].end_s = 50.0;  // middle 45
  SolveOptions options;
  EXPECT_DOUBLE_EQ(BiasReferenceTime(p, {true, false, true}, options), 25.0);
  EXPECT_DOUBLE_EQ(BiasReferenceTime(p, {true, true, true}, options), 25.0);
  EXPECT_DOUBLE_EQ(BiasReferenceTime(p, {true, true, false}, options), 15.0);
  options.bias_reference_time_s = 7.0;
  EXPECT_DOUBLE_EQ(BiasReferenceTime(p, {true, true, true}, options), 7.0);
}

TEST(DriftFTest, MatchesTheFDistribution) {
  // F = ((χ²₀ − χ²₁)/3) / (χ²₁/10) = 6.552 is the 1 % point of F(3, 10).
  const auto p = DriftFTest(10.0 + 3.0 * 6.552, 10.0, 10);
  ASSERT_TRUE(p.has_value());
  EXPECT_NEAR(*p, 0.01, 2e-4);
  EXPECT_DOUBLE_EQ(*DriftFTest(10.0, 10.0, 10), 1.0);  // no improvement
  EXPECT_FALSE(DriftFTest(5.0, 0.0, 10).has_value());  // a perfect fit says nothing
}

TEST(IsPlausibleEstimate, RefusesDivergedScaleAnglesAndNonFinite) {
  ErrorModel m;
  EXPECT_TRUE(IsPlausibleEstimate(m));
  m.scale_factor_error.y() = 0.6;
  EXPECT_FALSE(IsPlausibleEstimate(m));
  m = ErrorModel{};
  m.theta_zx_rad = -0.7;
  EXPECT_FALSE(IsPlausibleEstimate(m));
  m = ErrorModel{};
  m.bias_mps2.x() = std::nan("");
  EXPECT_FALSE(IsPlausibleEstimate(m));
}

TEST(CovarianceScale, NeverShrinksAndTrustsFewResidualsLess) {
  EXPECT_DOUBLE_EQ(CovarianceScale(0.5, 5), 1.0);  // below the prior: kept at 1
  // 5 residuals at 3.7 times their expected square: 1σ × 1.4, not × 1.9.
  EXPECT_NEAR(std::sqrt(CovarianceScale(3.7 * 5, 5)), 1.38, 0.01);
  // 30 at that level: the evidence dominates, 1σ × 1.7.
  EXPECT_NEAR(std::sqrt(CovarianceScale(3.7 * 30, 30)), 1.74, 0.01);
  EXPECT_DOUBLE_EQ(CovarianceScale(20.0, 0), 3.0);  // (10 + 20)/(10 + 0)
}

}  // namespace
}  // namespace mpcal::internal
