// A bias that drifts linearly over the session (README, "Time-varying
// bias"): fitted besides the constant bias and chosen by a test at 1 % (a likelihood
// ratio with the sensor noise as weights, or an F test when the positions scatter beyond
// it).
#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "mpcal/cramer_rao.h"
#include "mpcal/distributions.h"
#include "mpcal/solve.h"
#include "solve/weights.h"
#include "solve_fixture.h"
#include "synthetic_positions.h"

namespace mpcal {
namespace {

using testing::ConsumerGrade;
using testing::CubeDirections;
using testing::kTestGravityMps2;
using testing::MakeSession;
using testing::Tilted;

using testing::kNoise;
using testing::kSamples;
constexpr double kDwellS = 10.0;
constexpr double kStepS = 12.0;

// The 26 cube positions held kDwellS each, one every kStepS, their means
// offset by a bias drift that reaches zero at the end of the last one.
// With `count` positions, the first of a shuffled cube.
testing::SyntheticSession DriftingSession(const Eigen::Vector3d& drift_mps2_per_s,
                                          std::mt19937_64& rng,
                                          std::size_t count = 26) {
  // In a random order: held in the cube's own order (x from −1 to +1), a
  // drift of the x bias would look like a scale-factor error.
  std::vector<Eigen::Vector3d> directions = CubeDirections();
  std::shuffle(directions.begin(), directions.end(), rng);
  directions.resize(count);
  auto session =
      MakeSession(ConsumerGrade(), Tilted(directions, 0.1, rng), kNoise, kSamples, rng);
  const double end_s =
      kStepS * (static_cast<double>(session.positions.size()) - 1) + kDwellS;
  for (std::size_t k = 0; k < session.positions.size(); ++k) {
    PositionObservation& p = session.positions[k];
    p.start_s = kStepS * static_cast<double>(k);
    p.end_s = p.start_s + kDwellS;
    const double dt = 0.5 * (p.start_s + p.end_s) - end_s;
    p.mean_mps2 += drift_mps2_per_s * dt;
    session.bound_positions[k].time_from_reference_s = dt;
  }
  return session;
}

TEST(FUpperTail, MatchesTabulatedQuantiles) {
  // F(3, 10) exceeds 6.552 with probability 1 %, F(3, 20) 3.098 with 5 %.
  EXPECT_NEAR(FUpperTail(6.552, 3, 10), 0.01, 2e-4);
  EXPECT_NEAR(FUpperTail(3.098, 3, 20), 0.05, 5e-4);
  EXPECT_EQ(FUpperTail(0.0, 3, 20), 1.0);
}

TEST(Solve, FindsABiasDriftAndReportsTheBiasAtTheMiddleOfTheSession) {
  std::mt19937_64 rng(41);
  const Eigen::Vector3d drift(2e-5, -1e-5, 3e-5);  // m/s² per s
  const auto session = DriftingSession(drift, rng);
  const SolveResult r = Solve(session.positions, SolveOptions{});
  ASSERT_TRUE(r.converged()) << r.message;
  ASSERT_TRUE(r.bias_drift_p_value.has_value());
  ASSERT_TRUE(r.bias_drift.has_value()) << "p = " << *r.bias_drift_p_value;
  EXPECT_LT(r.bias_drift->p_value, 0.01);
  double mean_time_s = 0.0;
  for (const auto& p : session.positions) mean_time_s += 0.5 * (p.start_s + p.end_s);
  mean_time_s /= static_cast<double>(session.positions.size());
  EXPECT_NEAR(r.bias_drift->reference_time_s, mean_time_s, 1e-9);
  // The truth and the bound at the estimate's reference time.
  ErrorModel truth = ConsumerGrade();
  truth.bias_mps2 += drift * (mean_time_s - session.positions.back().end_s);
  auto bound_positions = session.bound_positions;
  for (std::size_t k = 0; k < bound_positions.size(); ++k) {
    const auto& p = session.positions[k];
    bound_positions[k].time_from_reference_s = 0.5 * (p.start_s + p.end_s) - mean_time_s;
  }
  const Eigen::Matrix<double, 9, 1> bound =
      CramerRaoBoundWithDrift(truth, bound_positions, kTestGravityMps2)
          .diagonal()
          .cwiseSqrt();
  const Eigen::Matrix<double, 9, 1> error = ToVector(r.estimate) - ToVector(truth);
  for (int i = 0; i < 9; ++i) {
    EXPECT_LT(std::abs(error[i]), 4.0 * bound[i]) << kParameterNames[i];
    // The reported 1σ is that of the model with the drift.
    EXPECT_NEAR(ToVector(r.std)[i] / bound[i], 1.0, 0.35) << kParameterNames[i];
  }
  for (int i = 0; i < 3; ++i) {
    EXPECT_LT(std::abs(r.bias_drift->mps2_per_s[i] - drift[i]),
              4.0 * r.bias_drift->std_mps2_per_s[i]);
  }
  // Without the drift model the same session is fitted worse.
  SolveOptions constant;
  constant.consider_bias_drift = false;
  const SolveResult c = Solve(session.positions, constant);
  EXPECT_FALSE(c.bias_drift.has_value());
  EXPECT_GT(c.residual_rms_after_mps2, 2.0 * r.residual_rms_after_mps2);
}

TEST(Solve, ChoosesNoDriftWhereThereIsNone) {
  std::mt19937_64 rng(42);
  int chosen = 0;
  int tested = 0;
  SolveOptions options;
  options.cross_validate = false;
  options.split_half_check = false;
  for (int s = 0; s < 100; ++s) {
    const SolveResult r =
        Solve(DriftingSession(Eigen::Vector3d::Zero(), rng).positions, options);
    chosen += r.bias_drift.has_value();
    tested += r.bias_drift_p_value.has_value();
  }
  EXPECT_EQ(tested, 100);
  // Binomial(100, 0.01): 1 expected, 5 or more with probability 0.3 %.
  EXPECT_LE(chosen, 4);
}

// 15 positions leave 3 redundant ones beside the drift's 12 parameters. The
// noise of each mean is known from its 1000 samples, so the drop in χ² is
// tested against χ²(3); an F(3, 3) test, which estimates the noise level
// from the 3 redundant residuals, rejects at 1 % only beyond F = 29.5 and
// misses most such drifts (they went into the scatter and widened every
// 1σ up to 3.6 times the bound in mpcal_accuracy_bench).
TEST(Solve, FindsADriftAtFewRedundantPositionsAndNoneWhereThereIsNone) {
  std::mt19937_64 rng(43);
  SolveOptions options;
  options.cross_validate = false;
  options.split_half_check = false;
  int found = 0;
  int false_alarms = 0;
  int tested = 0;
  for (int s = 0; s < 100; ++s) {
    // ±4.5e-3 m/s² at the ends of the 3 min session: ±5σ of a position's mean.
    const Eigen::Vector3d drift(5e-5, -5e-5, 5e-5);  // m/s² per s
    const SolveResult with = Solve(DriftingSession(drift, rng, 15).positions, options);
    const SolveResult without =
        Solve(DriftingSession(Eigen::Vector3d::Zero(), rng, 15).positions, options);
    found += with.bias_drift.has_value();
    false_alarms += without.bias_drift.has_value();
    tested +=
        with.bias_drift_p_value.has_value() && without.bias_drift_p_value.has_value();
  }
  EXPECT_EQ(tested, 100);
  EXPECT_GE(found, 95);
  // Binomial(100, 0.01): 1 expected, 5 or more with probability 0.3 %.
  EXPECT_LE(false_alarms, 4);
}

}  // namespace
}  // namespace mpcal
