// The rules inside AnalyzeRepeatability's steps (src/repeat/repeat_steps.h):
// the spread, the chi-square verdict, and the trials that do not compare.
#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mpcal/error.h"
#include "repeat/repeat_steps.h"

namespace mpcal::internal {
namespace {

TEST(SetSpread, MeanAndBothStandardDeviations) {
  ParameterRepeatability out;
  SetSpread({1.0, 2.0, 3.0, 6.0}, out);
  EXPECT_DOUBLE_EQ(out.mean, 3.0);
  EXPECT_DOUBLE_EQ(out.std_population, std::sqrt(14.0 / 4.0));
  EXPECT_DOUBLE_EQ(out.std_sample, std::sqrt(14.0 / 3.0));
}

TEST(SetSpread, IdenticalTrialsHaveExactlyZeroSpread) {
  ParameterRepeatability out;
  SetSpread({0.1 + 0.2, 0.1 + 0.2, 0.1 + 0.2}, out);
  EXPECT_EQ(out.mean, 0.1 + 0.2);
  EXPECT_EQ(out.std_sample, 0.0);
}

TEST(SetVerdict, ChiSquareAroundTheWeightedMean) {
  // Two trials 3σ apart in their combined 1σ: χ² = 9 with 1 dof, p = 0.0027.
  ParameterRepeatability out;
  out.values = {0.0, 3.0 * std::sqrt(2.0)};
  out.trial_std = {1.0, 1.0};
  SetVerdict(0.01, out);
  EXPECT_NEAR(*out.chi2, 9.0, 1e-12);
  EXPECT_NEAR(*out.p_value, 0.0026998, 1e-6);
  EXPECT_TRUE(*out.changed);
  SetVerdict(0.001, out);
  EXPECT_FALSE(*out.changed);
}

TEST(CheckTrialsCompare, RefusesAnotherGravityWithTheSettingsThatWouldFixIt) {
  std::vector<Calibration> trials(2);
  trials[1].gravity_mps2 = trials[0].gravity_mps2 + 0.01;
  try {
    CheckTrialsCompare(trials, {}, RepeatabilityOptions{});
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("do not compare"));
    EXPECT_EQ(e.kind(), ErrorKind::kSession);
    EXPECT_EQ(e.advice().stage, Stage::kCalibrate);
    ASSERT_EQ(e.advice().settings.size(), 3u);
    EXPECT_EQ(e.advice().settings[0].option, Option::kGravity);
    EXPECT_EQ(e.advice().settings[1].option, Option::kLatitude);
    EXPECT_EQ(e.advice().settings[2].option, Option::kHeight);
  }
  trials[1].gravity_mps2 = trials[0].gravity_mps2;
  EXPECT_NO_THROW(CheckTrialsCompare(trials, {}, RepeatabilityOptions{}));
}

}  // namespace
}  // namespace mpcal::internal
