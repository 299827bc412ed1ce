#include "mpcal/verdict.h"

#include <vector>

#include <gtest/gtest.h>

namespace mpcal {
namespace {

// A converged fit of 20 positions whose residuals are what the noise
// explains, a constant bias and halves that agree.
CalibrateResult GoodResult() {
  CalibrateResult r;
  r.solve.status = SolveStatus::kConverged;
  r.solve.used = std::vector<bool>(20, true);
  r.solve.variance_factor = 1.0;
  r.solve.bias_drift_p_value = 0.4;
  SplitHalfSummary split;
  SplitHalfComparison c;
  c.determined = true;
  c.p_value = 0.5;
  split.comparisons = {c, c};
  r.solve.split_half = split;
  r.mps2_per_unit = 1.0;
  return r;
}

const Check& Find(const std::vector<Check>& checks, CheckKind kind) {
  for (const Check& c : checks) {
    if (c.kind == kind) return c;
  }
  ADD_FAILURE() << "no check " << ToString(kind);
  return checks.front();
}

TEST(Verdict, GoodSessionIsGoodEverywhere) {
  const auto checks = JudgeCalibration(GoodResult(), CalibrateOptions{});
  ASSERT_EQ(checks.size(), 5u);  // no gyroscope
  EXPECT_EQ(Worst(checks), Verdict::kGood);
  EXPECT_EQ(Find(checks, CheckKind::kPositions).count, 20);
  EXPECT_DOUBLE_EQ(Find(checks, CheckKind::kPositions).value, 11.0);  // 20 − 9
}

TEST(Verdict, HalvesThatDisagreeSayDoNotUse) {
  CalibrateResult r = GoodResult();
  r.solve.split_half->comparisons[0].p_value = 1e-4;
  r.solve.split_half->comparisons[0].disagree = true;
  const auto checks = JudgeCalibration(r, CalibrateOptions{});
  const Check& c = Find(checks, CheckKind::kSplitHalf);
  EXPECT_EQ(c.verdict, Verdict::kDoNotUse);
  EXPECT_EQ(c.finding, CheckFinding::kSplitDisagree);
  EXPECT_DOUBLE_EQ(c.value, 1e-4);
  EXPECT_DOUBLE_EQ(c.limit, 0.005);  // the check's 1 % over 2 splits
}

TEST(Verdict, ResidualsBeyondTheNoiseAskForALook) {
  CalibrateResult r = GoodResult();
  // χ² = 3 × 11 on 11 degrees of freedom: p ≈ 5e-4, below 1 %.
  r.solve.variance_factor = 3.0;
  const auto checks = JudgeCalibration(r, CalibrateOptions{});
  const Check& c = Find(checks, CheckKind::kFit);
  EXPECT_EQ(c.verdict, Verdict::kLookAt);
  EXPECT_EQ(c.finding, CheckFinding::kFitBeyondNoise);
  EXPECT_LT(c.limit, kFitSignificance);
  // 1.5 × 11 is within chance (p ≈ 0.12).
  r.solve.variance_factor = 1.5;
  const auto within = JudgeCalibration(r, CalibrateOptions{});
  EXPECT_EQ(Find(within, CheckKind::kFit).verdict, Verdict::kGood);
}

TEST(Verdict, ExcludedOutlierAsksForALook) {
  CalibrateResult r = GoodResult();
  r.solve.used[3] = false;
  const auto checks = JudgeCalibration(r, CalibrateOptions{});
  EXPECT_EQ(Find(checks, CheckKind::kFit).finding, CheckFinding::kOutliersExcluded);
  EXPECT_EQ(Find(checks, CheckKind::kFit).count, 1);
  EXPECT_EQ(Find(checks, CheckKind::kPositions).count, 19);
}

TEST(Verdict, UnconvergedFitAndUndeterminedGyroscopeSayDoNotUse) {
  CalibrateResult r = GoodResult();
  r.solve.status = SolveStatus::kNoConvergence;
  GyroResult g;
  g.status = GyroStatus::kUndetermined;
  GyroFinding too_few;
  too_few.kind = GyroFindingKind::kTooFewTurns;
  g.findings.push_back(too_few);
  r.gyro = g;
  const auto checks = JudgeCalibration(r, CalibrateOptions{});
  EXPECT_EQ(Find(checks, CheckKind::kFit).verdict, Verdict::kDoNotUse);
  EXPECT_EQ(Find(checks, CheckKind::kGyroscope).finding,
            CheckFinding::kGyroNotCalibrated);
  EXPECT_EQ(Worst(checks), Verdict::kDoNotUse);
}

}  // namespace
}  // namespace mpcal
