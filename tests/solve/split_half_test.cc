// The split-half check inside the fit (docs/method.md §9): two halves of one
// session calibrated alone must agree within their combined 1σ.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "mpcal/solve.h"
#include "solve/split_half.h"
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

// The 26 cube directions twice, in two rounds: each half by time and each
// alternate half holds every direction.
std::vector<Eigen::Vector3d> TwoRounds() {
  std::vector<Eigen::Vector3d> d = CubeDirections();
  const std::vector<Eigen::Vector3d> again = CubeDirections();
  d.insert(d.end(), again.begin(), again.end());
  return d;
}

TEST(SplitHalf, HalvesOfAWhiteNoiseSessionAgree) {
  std::mt19937_64 rng(31);
  int disagreeing = 0;
  double sum_sq = 0.0;
  int values = 0;
  constexpr int kSessions = 20;
  for (int s = 0; s < kSessions; ++s) {
    const auto session = MakeSession(
        ConsumerGrade(), Tilted(TwoRounds(), 0.1, rng), kNoise, kSamples, rng);
    SolveOptions options;
    options.cross_validate = false;
    const SolveResult r = Solve(session.positions, options);
    ASSERT_TRUE(r.split_half.has_value());
    ASSERT_EQ(r.split_half->comparisons.size(), 2u);
    for (const SplitHalfComparison& c : r.split_half->comparisons) {
      ASSERT_TRUE(c.determined);
      EXPECT_EQ(c.positions_first, 26);
      EXPECT_EQ(c.positions_second, 26);
      ASSERT_EQ(c.z.size(), 9u);
      disagreeing += c.disagree;
      for (double z : c.z) sum_sq += z * z;
      values += 9;
    }
  }
  // 360 values of z: RMS 1 ± 0.04 for honest 1σ (±0.15 allows for the
  // correlation of the nine parameters of one split).
  EXPECT_NEAR(std::sqrt(sum_sq / values), 1.0, 0.15);
  // 40 tests at 1 %: 0.4 expected, 3 or more with probability 0.8 %.
  EXPECT_LE(disagreeing, 2);
}

TEST(SplitHalf, ABiasThatJumpsBetweenTheHalvesWidensThe1Sigma) {
  std::mt19937_64 rng(32);
  auto session =
      MakeSession(ConsumerGrade(), Tilted(TwoRounds(), 0.1, rng), kNoise, kSamples, rng);
  // The second round's readings offset by ten times the noise of a mean.
  const double sigma_mean = kNoise.norm() / std::sqrt(3.0 * kSamples);
  for (std::size_t k = 26; k < session.positions.size(); ++k) {
    session.positions[k].mean_mps2 += Eigen::Vector3d(10.0 * sigma_mean, 0.0, 0.0);
  }
  SolveOptions plain;
  plain.cross_validate = false;
  plain.split_half_check = false;
  SolveOptions checked = plain;
  checked.split_half_check = true;
  const SolveResult without = Solve(session.positions, plain);
  const SolveResult with = Solve(session.positions, checked);
  ASSERT_TRUE(with.split_half.has_value());
  const SplitHalfComparison& by_time = with.split_half->comparisons[0];
  ASSERT_EQ(by_time.kind, SplitKind::kByTime);
  ASSERT_TRUE(by_time.determined);
  EXPECT_TRUE(by_time.disagree);
  EXPECT_GT(std::abs(by_time.z[0]), 4.0);  // bias x
  const double widening = with.split_half->widening;
  EXPECT_GE(widening, std::sqrt(by_time.chi2 / by_time.dof) * (1 - 1e-12));
  EXPECT_GT(widening, 1.5);
  // The estimate is the same; every 1σ is widened by the factor.
  EXPECT_NEAR(with.estimate.bias_mps2.x(), without.estimate.bias_mps2.x(), 1e-12);
  // A named vector, not `auto`: an Eigen expression would outlive its operands.
  const Eigen::Matrix<double, 9, 1> ratio =
      ToVector(with.std).cwiseQuotient(ToVector(without.std));
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(ratio[i], widening, 1e-9 * widening);
  ASSERT_FALSE(with.warnings.empty());
  EXPECT_NE(with.warnings.back().find("widened"), std::string::npos);
}

// Whether each half holds, for every axis, an orientation with that axis
// up and one with it down (within 60°): the halves span the sphere.
bool SpansTheSphere(const std::vector<PositionObservation>& positions,
                    const std::vector<std::size_t>& half) {
  for (int axis = 0; axis < 3; ++axis) {
    bool up = false;
    bool down = false;
    for (std::size_t k : half) {
      const double c = positions[k].mean_mps2.normalized()[axis];
      up = up || c > 0.5;
      down = down || c < -0.5;
    }
    if (!up || !down) return false;
  }
  return true;
}

TEST(InterleavedHalves, EachHalfSpansTheSphereWhateverTheOrder) {
  std::mt19937_64 rng(34);
  // The cube's own order, and every position followed by its opposite (an
  // up/down pair held in turn: odd and even positions would put every
  // "up" in one half).
  std::vector<Eigen::Vector3d> in_turn;
  for (const Eigen::Vector3d& u : CubeDirections()) {
    if (u.x() + 1e-3 * u.y() + 1e-6 * u.z() > 0.0) continue;
    in_turn.push_back(u);
    in_turn.push_back(-u);
  }
  ASSERT_EQ(in_turn.size(), 26u);
  for (const auto& directions : {CubeDirections(), in_turn}) {
    const auto session =
        MakeSession(ConsumerGrade(), Tilted(directions, 0.1, rng), kNoise, kSamples, rng);
    const auto halves = internal::InterleavedHalves(session.positions);
    EXPECT_EQ(halves[0].size(), 13u);
    EXPECT_EQ(halves[1].size(), 13u);
    EXPECT_TRUE(SpansTheSphere(session.positions, halves[0]));
    EXPECT_TRUE(SpansTheSphere(session.positions, halves[1]));
  }
}

// The standard session: the 26 cube positions once, 13 + 13 interleaved
// (4 redundant each). White noise, then means scattering three times
// more than their samples' noise says (hand tremor): the halves take the
// whole session's scatter, which 17 redundant positions show and 4 could
// not. Honest 1σ: RMS z near 1, about 1 % of the χ² tests rejecting.
void ExpectHonestInterleavedSplits(double excess, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  int disagreeing = 0;
  double sum_sq = 0.0;
  int values = 0;
  constexpr int kSessions = 30;
  for (int s = 0; s < kSessions; ++s) {
    auto session = MakeSession(ConsumerGrade(),
                               Tilted(CubeDirections(), 0.1, rng),
                               excess * kNoise,
                               kSamples,
                               rng);
    for (auto& p : session.positions) p.sample_std_mps2 /= excess;
    SolveOptions options;
    options.cross_validate = false;
    const SolveResult r = Solve(session.positions, options);
    ASSERT_TRUE(r.split_half.has_value());
    const SplitHalfComparison& c = r.split_half->comparisons.at(1);
    ASSERT_EQ(c.kind, SplitKind::kInterleaved);
    ASSERT_TRUE(c.determined) << "session " << s;
    EXPECT_EQ(c.positions_first + c.positions_second, 26);
    disagreeing += c.disagree;
    for (double z : c.z) sum_sq += z * z;
    values += static_cast<int>(c.z.size());
  }
  // 270 values of z: RMS 1 ± 0.05 for honest 1σ; ±0.2 allows for the
  // correlation of the nine parameters and the halves' own linearisation.
  EXPECT_NEAR(std::sqrt(sum_sq / values), 1.0, 0.2);
  // 30 tests at 1 %: 0.3 expected, 3 or more with probability 0.3 %.
  EXPECT_LE(disagreeing, 2);
}

TEST(SplitHalf, PossibleOnTheStandard26PositionSessionWithWhiteNoise) {
  ExpectHonestInterleavedSplits(1.0, 35);
}

TEST(SplitHalf, HalvesOfAScatteringSessionTakeItsScatter) {
  ExpectHonestInterleavedSplits(3.0, 36);
}

TEST(SplitHalf, NotPossibleWhenAHalfCannotDetermineTheModel) {
  std::mt19937_64 rng(33);
  std::vector<Eigen::Vector3d> directions = CubeDirections();
  directions.resize(14);
  const auto session =
      MakeSession(ConsumerGrade(), Tilted(directions, 0.1, rng), kNoise, kSamples, rng);
  const SolveResult r = Solve(session.positions, SolveOptions{});
  ASSERT_TRUE(r.split_half.has_value());
  for (const SplitHalfComparison& c : r.split_half->comparisons) {
    EXPECT_FALSE(c.determined);
    EXPECT_TRUE(c.z.empty());
  }
  EXPECT_EQ(r.split_half->widening, 1.0);
}

// Two splits share the check's 1 %: a split at p = 0.007 is chance (each is
// tested at 0.5 %), one at p = 0.003 is not, and a split that could not be
// made leaves the whole 1 % to the other.
SplitHalfComparison Judged(double chi2, double p_value, bool determined = true) {
  SplitHalfComparison c;
  c.determined = determined;
  c.chi2 = chi2;
  c.dof = 9;
  c.p_value = p_value;
  return c;
}

TEST(SplitHalf, TheSplitsShareTheSignificance) {
  std::vector<SplitHalfComparison> both = {Judged(22.3, 0.007), Judged(9.0, 0.44)};
  EXPECT_EQ(internal::JudgeSplits(both, 0.01), 1.0);
  EXPECT_FALSE(both[0].disagree);

  std::vector<SplitHalfComparison> beyond = {Judged(25.0, 0.003), Judged(30.0, 0.0004)};
  EXPECT_DOUBLE_EQ(internal::JudgeSplits(beyond, 0.01), std::sqrt(30.0 / 9.0));
  EXPECT_TRUE(beyond[0].disagree);
  EXPECT_TRUE(beyond[1].disagree);

  std::vector<SplitHalfComparison> one = {Judged(22.3, 0.007),
                                          Judged(0.0, 1.0, /*determined=*/false)};
  EXPECT_DOUBLE_EQ(internal::JudgeSplits(one, 0.01), std::sqrt(22.3 / 9.0));
  EXPECT_TRUE(one[0].disagree);
  EXPECT_FALSE(one[1].disagree);
}

}  // namespace
}  // namespace mpcal
