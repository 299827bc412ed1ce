// The named steps of static detection, each on the rule it carries.
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "detect/detect_steps.h"
#include "findings.h"
#include "mpcal/error.h"

namespace mpcal {
namespace {

using internal::FindStillRuns;
using internal::MergeAcrossBumps;
using internal::Piece;
using internal::StillRuns;
using internal::TrimSettling;

using RunRange = std::pair<std::size_t, std::size_t>;
RunRange Span(std::size_t begin, std::size_t end) { return {begin, end}; }

std::vector<double> Times(std::size_t n, double period_s) {
  std::vector<double> t(n);
  for (std::size_t i = 0; i < n; ++i) t[i] = static_cast<double>(i) * period_s;
  return t;
}

TEST(FindStillRuns, RunsAreTheStretchesAtOrBelowTheThreshold) {
  const std::vector<double> t = Times(10, 0.1);
  const double inf = std::numeric_limits<double>::infinity();
  //                           0    1    2    3    4    5    6    7    8    9
  const std::vector<double> stat{inf, 1.0, 1.0, 5.0, 2.0, 2.0, 2.0, 9.0, 1.0, inf};
  const StillRuns r = FindStillRuns(t, stat, 1, 8, 2.0, 1.0);
  ASSERT_EQ(r.runs.size(), 3u);
  EXPECT_EQ(r.runs[0], Span(1, 3));
  EXPECT_EQ(r.runs[1], Span(4, 7));
  // A run still open at the last centre ends there.
  EXPECT_EQ(r.runs[2], Span(8, 9));
  EXPECT_EQ(r.still_count, 6u);
}

TEST(FindStillRuns, ATimeGapLongerThanAWindowEndsARun) {
  std::vector<double> t = Times(8, 0.1);
  for (std::size_t i = 4; i < t.size(); ++i) t[i] += 5.0;  // 5 s of missing data
  const std::vector<double> stat(8, 0.5);
  const StillRuns r = FindStillRuns(t, stat, 0, 7, 1.0, 1.0);
  ASSERT_EQ(r.runs.size(), 2u);
  EXPECT_EQ(r.runs[0].second, 4u);
  EXPECT_EQ(r.runs[1].first, 4u);
}

TEST(TrimSettling, TrimsTheSettlingAtBothEndsAndDropsAFlicker) {
  const std::vector<double> t = Times(200, 0.01);  // 100 Hz
  const std::vector<Eigen::Vector3d> a(200, Eigen::Vector3d(0, 0, 9.8));
  StillRuns runs;
  runs.runs = {{0, 100}, {150, 160}};  // 0.99 s, and a 0.09 s flicker
  double longest = 0.0;
  const std::vector<Piece> pieces = TrimSettling(t, a, runs, 0.305, &longest);
  ASSERT_EQ(pieces.size(), 1u);
  // Kept: t in [0.305, 0.99 - 0.305] s, samples 31 to 68 inclusive.
  EXPECT_EQ(pieces[0].begin, 31u);
  EXPECT_EQ(pieces[0].end, 69u);
  EXPECT_NEAR(longest, 0.99, 1e-12);
  EXPECT_NEAR((pieces[0].mean - Eigen::Vector3d(0, 0, 9.8)).norm(), 0.0, 1e-12);
}

TEST(MergeAcrossBumps, MergesAShortBumpAtTheSameOrientationOnly) {
  const std::vector<double> t = Times(1000, 0.01);
  DetectOptions o;  // window 1 s, settle 0.3 s, merge gap 1 s, merge angle 3 deg
  const Eigen::Vector3d up(0, 0, 9.8);
  // Gap of 2.5 s between the pieces: a bump of 2.5 - 0.6 - 1.0 = 0.9 s < 1 s.
  const Piece first{0, 300, up};
  const Piece same{550, 900, up + Eigen::Vector3d(0.2, 0, 0)};  // 1.2 deg away
  int merged = 0;
  auto groups = MergeAcrossBumps(t, {first, same}, Eigen::Vector3d::Zero(), o, &merged);
  EXPECT_EQ(groups.size(), 1u);
  EXPECT_EQ(merged, 1);
  // Tilted by 6 deg: two positions.
  const Piece tilted{550, 900, Eigen::AngleAxisd(0.1047, Eigen::Vector3d::UnitX()) * up};
  merged = 0;
  groups = MergeAcrossBumps(t, {first, tilted}, Eigen::Vector3d::Zero(), o, &merged);
  EXPECT_EQ(groups.size(), 2u);
  EXPECT_EQ(merged, 0);
  // A longer bump (gap 2.7 s: 1.1 s of bump): two positions.
  const Piece later{570, 900, up};
  groups = MergeAcrossBumps(t, {first, later}, Eigen::Vector3d::Zero(), o, &merged);
  EXPECT_EQ(groups.size(), 2u);
}

TEST(Diagnose, TooShortSuggestsTheMinimumTheLongestStretchPasses) {
  DetectResult r;
  r.longest_still_s = 1.8;
  r.dropped_short = 4;
  r.threshold = 0.1;
  r.quiet_level = 0.03;
  DetectOptions o;
  const DetectFinding f = internal::Diagnose(r, o, 60.0, true, "");
  EXPECT_EQ(f.kind, DetectOutcome::kTooShort);
  // 90 % of the stretch after the settling, to a tenth below: 0.9 x 1.5 = 1.35.
  EXPECT_DOUBLE_EQ(f.suggested_min_static_s, 1.3);
  EXPECT_DOUBLE_EQ(f.suggested_settle_s, 0.15);
  ASSERT_EQ(f.advice.settings.size(), 3u);
  EXPECT_EQ(f.advice.settings[0].option, Option::kDetectMinStatic);
  EXPECT_EQ(f.advice.settings[0].value, "1.3");
  EXPECT_EQ(f.advice.settings[1].option, Option::kDetectSettle);
  EXPECT_EQ(f.advice.settings[2].option, Option::kDetectThreshold);
  // A capped threshold is not advised to be raised.
  r.threshold_capped = true;
  EXPECT_EQ(internal::Diagnose(r, o, 60.0, true, "").advice.settings.size(), 2u);
  // No still window at all: the cap is what to raise.
  const DetectFinding never = internal::Diagnose(r, o, 60.0, false, "");
  EXPECT_EQ(never.kind, DetectOutcome::kNeverStill);
  EXPECT_TRUE(test::Names(never.advice, Option::kDetectMaxStill));
  // A plain sentence names no option.
  EXPECT_THAT(Describe(f), ::testing::Not(::testing::HasSubstr("--")));
}

TEST(DetectStatic, RefusesAWindowShorterThanTwoSamples) {
  Recording r;
  for (int i = 0; i < 500; ++i) {
    r.time_s.push_back(i * 0.01);
    r.accel.emplace_back(0.0, 0.0, 9.8 + 0.01 * std::sin(i));
  }
  DetectOptions o;
  o.window_s = 0.015;  // 1.5 samples at 100 Hz
  try {
    DetectStatic(r, o);
    FAIL() << "expected an Error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kOption);
    ASSERT_TRUE(test::Names(e.advice(), Option::kDetectWindow));
    EXPECT_EQ(e.advice().settings[0].value, "0.03");
  }
  o.window_s = 0.03;  // three samples: accepted
  EXPECT_NO_THROW(DetectStatic(r, o));
}

}  // namespace
}  // namespace mpcal
