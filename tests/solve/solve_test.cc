#include "mpcal/solve.h"

#include <cmath>
#include <random>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mpcal/cramer_rao.h"
#include "mpcal/error.h"
#include "solve/weights.h"
#include "solve_fixture.h"
#include "synthetic_positions.h"

namespace mpcal {
namespace {

using testing::ConsumerGrade;
using testing::CubeDirections;
using ::testing::HasSubstr;
using testing::kTestGravityMps2;
using testing::MakeSession;
using testing::Tilted;

constexpr double kNoiseFreeTolerance = 1e-8;  // packed parameters, noise-free means
using testing::kNoise;
using testing::kSamples;

TEST(SolveOptions, DefaultsAreValid) { EXPECT_EQ(SolveOptions{}.Validate(), ""); }

TEST(InitialiseSixPosition, IsExactForAxisAlignedPositionsWithoutAngles) {
  ErrorModel truth = ConsumerGrade();
  truth.theta_yz_rad = truth.theta_zx_rad = truth.theta_zy_rad = 0.0;
  std::mt19937_64 rng(1);
  std::vector<Eigen::Vector3d> axes;
  for (int i = 0; i < 3; ++i) {
    axes.push_back(Eigen::Vector3d::Unit(i));
    axes.push_back(-Eigen::Vector3d::Unit(i));
  }
  const auto session = MakeSession(truth, axes, Eigen::Vector3d::Constant(1e-12), 1, rng);
  const ErrorModel init = InitialiseSixPosition(session.positions, kTestGravityMps2);
  EXPECT_LT((init.bias_mps2 - truth.bias_mps2).norm(), 1e-9);
  EXPECT_LT((init.scale_factor_error - truth.scale_factor_error).norm(), 1e-9);
}

TEST(Solve, RecoversConsumerGradeErrorsExactlyWithoutNoise) {
  std::mt19937_64 rng(2);
  const ErrorModel truth = ConsumerGrade();
  const auto session = MakeSession(
      truth, Tilted(CubeDirections(), 0.1, rng), Eigen::Vector3d::Constant(1e-9), 1, rng);
  const SolveResult r = Solve(session.positions, SolveOptions{});
  ASSERT_TRUE(r.converged()) << r.message;
  EXPECT_LT((ToVector(r.estimate) - ToVector(truth)).cwiseAbs().maxCoeff(),
            kNoiseFreeTolerance);
  EXPECT_LT(r.residual_rms_after_mps2, 1e-8);
  EXPECT_GT(r.residual_rms_before_mps2, 0.5);
}

// The estimator reaches the Cramér-Rao bound (docs/method.md §3.8): over many
// sessions the errors, divided by the bound's 1σ, have RMS 1, and the 1σ the
// solver reports matches the bound.
TEST(Solve, ReachesTheCramerRaoBound) {
  constexpr int kSessions = 150;
  std::mt19937_64 rng(3);
  const ErrorModel truth = ConsumerGrade();
  SolveOptions options;
  options.cross_validate = false;  // does not change the estimate; saves time
  double sum_squared_ratio = 0.0;
  Eigen::Matrix<double, 9, 1> reported_over_bound = Eigen::Matrix<double, 9, 1>::Zero();
  for (int s = 0; s < kSessions; ++s) {
    const auto session =
        MakeSession(truth, Tilted(CubeDirections(), 0.1, rng), kNoise, kSamples, rng);
    const SolveResult r = Solve(session.positions, options);
    ASSERT_TRUE(r.converged());
    const Eigen::Matrix<double, 9, 1> bound =
        CramerRaoBound(truth, session.bound_positions, kTestGravityMps2)
            .diagonal()
            .cwiseSqrt();
    const Eigen::Matrix<double, 9, 1> ratio =
        (ToVector(r.estimate) - ToVector(truth)).cwiseQuotient(bound);
    sum_squared_ratio += ratio.squaredNorm();
    reported_over_bound += ToVector(r.std).cwiseQuotient(bound);
  }
  // 1350 normalised errors: the RMS of a unit normal scatters by ~2 %.
  const double rms_ratio = std::sqrt(sum_squared_ratio / (9.0 * kSessions));
  EXPECT_GT(rms_ratio, 0.9);
  EXPECT_LT(rms_ratio, 1.15);
  reported_over_bound /= kSessions;
  for (int i = 0; i < 9; ++i) {
    EXPECT_NEAR(reported_over_bound[i], 1.0, 0.1) << kParameterNames[i];
  }
}

// Fourteen positions whose means scatter 1.9 times more than their noise
// says: five residuals are enough evidence when the median of their
// standardised squares is far beyond chance (the scatter test at 1 %), and
// the 1σ then follows the real scatter, not the understated noise, nor
// twice it.
TEST(Solve, FourteenPositionsScatteringTwiceTheirNoiseGetAnHonest1Sigma) {
  std::mt19937_64 rng(11);
  const ErrorModel truth = ConsumerGrade();
  std::vector<Eigen::Vector3d> directions;
  const auto cube = CubeDirections();
  for (std::size_t k = 0; k < cube.size(); k += 2) directions.push_back(cube[k]);
  directions.push_back(cube[1]);
  ASSERT_EQ(directions.size(), 14u);
  constexpr double kExcess = 1.9;
  auto session =
      MakeSession(truth, Tilted(directions, 0.1, rng), kExcess * kNoise, kSamples, rng);
  const Eigen::Matrix<double, 9, 1> real_bound =
      CramerRaoBound(truth, session.bound_positions, kTestGravityMps2)
          .diagonal()
          .cwiseSqrt();
  for (auto& p : session.positions) p.sample_std_mps2 /= kExcess;
  const SolveResult r = Solve(session.positions, SolveOptions{});
  ASSERT_TRUE(r.converged()) << r.message;
  EXPECT_GT(r.position_scatter_mps2, 0.0);
  const Eigen::Matrix<double, 9, 1> ratio = ToVector(r.std).cwiseQuotient(real_bound);
  for (int i = 0; i < 9; ++i) {
    // Five residuals estimate the scatter to about ±1/sqrt(2·5) of itself.
    EXPECT_GT(ratio[i], 0.6) << kParameterNames[i];
    EXPECT_LT(ratio[i], 1.8) << kParameterNames[i];
  }
}

TEST(Solve, SixParameterModelHoldsTheAnglesAtZero) {
  std::mt19937_64 rng(4);
  ErrorModel truth = ConsumerGrade();
  truth.theta_yz_rad = truth.theta_zx_rad = truth.theta_zy_rad = 0.0;
  const auto session =
      MakeSession(truth, Tilted(CubeDirections(), 0.1, rng), kNoise, kSamples, rng);
  SolveOptions options;
  options.model = ModelKind::kBiasScale6;
  const SolveResult r = Solve(session.positions, options);
  ASSERT_TRUE(r.converged());
  EXPECT_EQ(r.estimate.theta_yz_rad, 0.0);
  EXPECT_EQ(r.std.theta_zy_rad, 0.0);
  const auto bound = CramerRaoBound(
      truth, session.bound_positions, kTestGravityMps2, ModelKind::kBiasScale6);
  for (int i = 0; i < 6; ++i) {
    EXPECT_LT(std::abs(ToVector(r.estimate)[i] - ToVector(truth)[i]),
              5.0 * std::sqrt(bound(i, i)))
        << kParameterNames[i];
  }
}

TEST(Solve, RefusesTooFewPositionsAndSuggestsTheSixParameterModel) {
  std::mt19937_64 rng(5);
  auto directions = CubeDirections();
  directions.resize(8);  // 9 parameters
  const auto session = MakeSession(ConsumerGrade(), directions, kNoise, kSamples, rng);
  try {
    Solve(session.positions, SolveOptions{});
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("8 static positions are too few"));
    // The six-parameter model as a fact: the words are the command's.
    ASSERT_EQ(e.advice().settings.size(), 1u);
    EXPECT_EQ(e.advice().settings[0].option, Option::kModel);
    EXPECT_EQ(e.advice().settings[0].value, "bias-scale-6");
  }
}

TEST(Solve, NamesTheParametersThatCoplanarPositionsLeaveUndetermined) {
  // Every direction in the x-y plane: nothing can tell bias z from the rest.
  std::mt19937_64 rng(6);
  std::vector<Eigen::Vector3d> planar;
  for (int k = 0; k < 16; ++k) {
    const double a = 2.0 * M_PI * k / 16.0;
    planar.emplace_back(std::cos(a), std::sin(a), 0.0);
  }
  ErrorModel truth = ConsumerGrade();
  const auto session = MakeSession(truth, planar, kNoise, kSamples, rng);
  try {
    Solve(session.positions, SolveOptions{});
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("do not determine"));
    EXPECT_THAT(e.what(), HasSubstr("scale_factor_error_z"));
  }
}

TEST(Solve, RejectsNonFiniteMeans) {
  std::mt19937_64 rng(7);
  auto session = MakeSession(ConsumerGrade(), CubeDirections(), kNoise, kSamples, rng);
  session.positions[3].mean_mps2.y() = std::nan("");
  EXPECT_THROW(Solve(session.positions, SolveOptions{}), Error);
}

// A position where the sensor was bumped: 0.05 m/s² off, ~60 times the noise
// of its mean.
constexpr double kBumpMps2 = 0.05;

testing::SyntheticSession SessionWithABump(std::mt19937_64& rng, std::size_t bumped) {
  auto session = MakeSession(
      ConsumerGrade(), Tilted(CubeDirections(), 0.1, rng), kNoise, kSamples, rng);
  session.positions[bumped].mean_mps2 +=
      kBumpMps2 * session.positions[bumped].mean_mps2.normalized();
  session.positions[bumped].start_s = 120.0;
  session.positions[bumped].end_s = 130.0;
  return session;
}

TEST(Solve, ExcludesABumpedPositionAndNamesIt) {
  std::mt19937_64 rng(8);
  const auto session = SessionWithABump(rng, 11);
  const SolveResult r = Solve(session.positions, SolveOptions{});
  ASSERT_TRUE(r.converged());
  EXPECT_FALSE(r.used[11]);
  EXPECT_EQ(std::count(r.used.begin(), r.used.end(), false), 1);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_THAT(r.warnings[0],
              HasSubstr("position 12 (120.0-130.0 s) excluded as an outlier"));
  // Back to an estimate consistent with its own 1σ.
  const Eigen::Matrix<double, 9, 1> z =
      (ToVector(r.estimate) - ToVector(ConsumerGrade())).cwiseQuotient(ToVector(r.std));
  EXPECT_LT(z.cwiseAbs().maxCoeff(), 3.5);
  // The bumped position is predicted by the fit without it: off by the bump.
  EXPECT_NEAR(r.cross_validation_residual_mps2[11], kBumpMps2, 0.1 * kBumpMps2);
}

TEST(Solve, KeepsEveryPositionOfACleanSession) {
  std::mt19937_64 rng(9);
  for (int s = 0; s < 20; ++s) {
    const auto session = MakeSession(
        ConsumerGrade(), Tilted(CubeDirections(), 0.1, rng), kNoise, kSamples, rng);
    const SolveResult r = Solve(session.positions, SolveOptions{});
    EXPECT_EQ(std::count(r.used.begin(), r.used.end(), false), 0);
  }
}

TEST(Solve, RobustLossesResistABumpWithoutExcludingIt) {
  std::mt19937_64 rng(10);
  const auto session = SessionWithABump(rng, 4);
  SolveOptions plain;
  plain.exclude_outliers = false;
  auto error_with = [&](RobustLoss loss) {
    SolveOptions o = plain;
    o.robust = loss;
    const SolveResult r = Solve(session.positions, o);
    EXPECT_TRUE(r.converged());
    EXPECT_TRUE(r.used[4]);
    // In units of the bound-level 1σ, so that bias and angles weigh alike.
    return (ToVector(r.estimate) - ToVector(ConsumerGrade()))
        .cwiseQuotient(ToVector(r.std))
        .norm();
  };
  const double plain_error = error_with(RobustLoss::kNone);
  // Huber bounds the bump's influence to that of a 1.345σ residual; Cauchy
  // all but removes it.
  EXPECT_LT(error_with(RobustLoss::kHuber), 0.5 * plain_error);
  EXPECT_LT(error_with(RobustLoss::kCauchy), 0.25 * plain_error);
}

TEST(Solve, CrossValidationResidualsExceedTheFittedOnes) {
  // A position left out of the fit cannot pull it: its predicted residual is
  // larger, by about 1/(1 − leverage) ≈ K/(K − 9) on average.
  std::mt19937_64 rng(12);
  const auto session = MakeSession(
      ConsumerGrade(), Tilted(CubeDirections(), 0.1, rng), kNoise, kSamples, rng);
  const SolveResult r = Solve(session.positions, SolveOptions{});
  ASSERT_EQ(r.cross_validation_residual_mps2.size(), session.positions.size());
  const double ratio = r.cross_validation_rms_mps2 / r.residual_rms_after_mps2;
  EXPECT_GT(ratio, 1.1);
  EXPECT_LT(ratio, 2.5);
}

TEST(CramerRaoBound, ShrinksAsOneOverTheNumberOfSamples) {
  const ErrorModel truth = ConsumerGrade();
  std::vector<BoundPosition> a, b;
  for (const auto& u : CubeDirections()) {
    a.push_back({u, kNoise, 1000});
    b.push_back({u, kNoise, 4000});
  }
  const auto ca = CramerRaoBound(truth, a, kTestGravityMps2);
  const auto cb = CramerRaoBound(truth, b, kTestGravityMps2);
  EXPECT_LT((ca - 4.0 * cb).norm(), 1e-9 * ca.norm());
}

TEST(CramerRaoBound, RefusesPositionsThatDetermineNothing) {
  std::vector<BoundPosition> same(12, {Eigen::Vector3d::UnitZ(), kNoise, 100});
  EXPECT_THROW(CramerRaoBound(ErrorModel{}, same, kTestGravityMps2), Error);
}

}  // namespace
}  // namespace mpcal
