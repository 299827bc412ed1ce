// Which measure of the gravity directions the turns use (turn_weights.h,
// ChooseDirections): the plain mean unless the hand's sway, estimated from
// the two measures' difference, errs more than the gyroscope's noise that
// carrying adds.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "gyro/turn_problem.h"
#include "gyro/turn_weights.h"

namespace mpcal {
namespace {

constexpr double kPeriodS = 0.01;
constexpr double kWhite = 0.01;   // rad/s per sample, at a scale of 1
constexpr double kWindowS = 1.0;  // each edge
// The carried mean's noise per tangent component: σ² dt W/3.
const double kCarryVariance = kWhite * kWhite * kPeriodS * kWindowS / 3.0;

// 200 turns whose plain and carried directions differ by the sway (σ per
// component) and the carrying's noise.
internal::TurnProblem Turns(double sway_sigma_rad, unsigned seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  internal::TurnProblem p;
  p.sample_period_s = kPeriodS;
  const double sigma = std::sqrt(sway_sigma_rad * sway_sigma_rad + kCarryVariance);
  auto edge = [&] {
    internal::EdgeDirections e;
    e.still = Eigen::Vector3d::UnitZ();
    e.carried =
        Eigen::Vector3d(sigma * normal(rng), sigma * normal(rng), 1.0).normalized();
    e.window_s = kWindowS;
    return e;
  };
  for (int k = 0; k < 200; ++k) {
    internal::TurnData t;
    t.from = edge();
    t.to = edge();
    internal::UseDirections(t.from.carried, t.to.carried, &t);
    p.turns.push_back(std::move(t));
  }
  return p;
}

TEST(ChooseDirections, WithoutSwayThePlainMeanAndNothingAdded) {
  internal::TurnProblem p = Turns(0.0, 1);
  const GyroDirections d = internal::ChooseDirections(kWhite, 1.0, &p);
  EXPECT_FALSE(d.carried);
  EXPECT_NEAR(d.carry_noise_rad, std::sqrt(kCarryVariance), 1e-12);
  // The sway's estimate is the difference less the carrying's noise: at most
  // a few of its standard errors (√(2/800) of the variance) above zero.
  EXPECT_LT(d.sway_rad * d.sway_rad, 0.15 * kCarryVariance);
  for (const internal::TurnData& t : p.turns) {
    EXPECT_EQ(t.u_from, t.from.still);
    EXPECT_EQ(t.u_to, t.to.still);
    EXPECT_NEAR(t.direction_variance_rad2, 2.0 * d.sway_rad * d.sway_rad, 1e-18);
    EXPECT_EQ(t.gyro_variance_raw2s2, 0.0);
  }
}

TEST(ChooseDirections, ASwayBeyondTheGyroscopesNoiseIsCarriedOut) {
  const double sway = 3.0 * std::sqrt(kCarryVariance);
  internal::TurnProblem p = Turns(sway, 2);
  const GyroDirections d = internal::ChooseDirections(kWhite, 1.0, &p);
  EXPECT_TRUE(d.carried);
  EXPECT_NEAR(d.sway_rad, sway, 0.1 * sway);
  for (const internal::TurnData& t : p.turns) {
    EXPECT_EQ(t.u_from, t.from.carried);
    EXPECT_EQ(t.direction_variance_rad2, 0.0);
    // Both windows' carrying noise, in raw units² s² (scale 1).
    EXPECT_NEAR(t.gyro_variance_raw2s2, 2.0 * kCarryVariance, 1e-18);
  }
}

TEST(ChooseDirections, ASwayBelowItIsWeighedNotCarried) {
  const double sway = 0.7 * std::sqrt(kCarryVariance);
  internal::TurnProblem p = Turns(sway, 3);
  const GyroDirections d = internal::ChooseDirections(kWhite, 1.0, &p);
  EXPECT_FALSE(d.carried);
  EXPECT_NEAR(d.sway_rad, sway, 0.25 * sway);
  EXPECT_NEAR(p.turns[0].direction_variance_rad2, 2.0 * d.sway_rad * d.sway_rad, 1e-18);
}

TEST(ChooseDirections, WithoutANominalScaleNothingChanges) {
  internal::TurnProblem p = Turns(0.01, 4);
  const GyroDirections d = internal::ChooseDirections(kWhite, 0.0, &p);
  EXPECT_FALSE(d.carried);
  EXPECT_EQ(d.carry_noise_rad, 0.0);
  EXPECT_EQ(p.turns[0].u_from, p.turns[0].from.carried);
}

}  // namespace
}  // namespace mpcal
