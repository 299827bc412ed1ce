// The steps of Verify on their own (src/trajectory/verify_steps.h): each
// carries one rule of the field verification.
#include "trajectory/verify_steps.h"

#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mpcal/error.h"

namespace mpcal::internal {
namespace {

using ::testing::HasSubstr;

// A straight walk east at 1 m/s from t0 + rest_s, sampled at 10 Hz.
TimedPath WalkEast(double t0, double rest_s, double length_s) {
  TimedPath p;
  for (double t = 0.0; t <= rest_s + length_s + 1e-9; t += 0.1) {
    p.time_s.push_back(t0 + t);
    p.position_m.emplace_back(std::max(0.0, t - rest_s), 0.0, 0.0);
  }
  return p;
}

TEST(ResolveAlignMode, AutoTakesTheCommonClockWhenTheSpansOverlapByHalf) {
  const ClockSpans half{
      .imu_begin_s = 0, .imu_end_s = 100, .ref_begin_s = 50, .ref_end_s = 150};
  EXPECT_EQ(ResolveAlignMode(TimeAlignMode::kAuto, half, true),
            TimeAlignMode::kCommonClock);
  const ClockSpans apart{
      .imu_begin_s = 0, .imu_end_s = 100, .ref_begin_s = 60, .ref_end_s = 160};
  EXPECT_EQ(ResolveAlignMode(TimeAlignMode::kAuto, apart, true),
            TimeAlignMode::kMotionStart);
  // Without a start-of-motion offset there is nothing else to take.
  EXPECT_EQ(ResolveAlignMode(TimeAlignMode::kAuto, apart, false),
            TimeAlignMode::kCommonClock);
  // An explicit mode is kept.
  EXPECT_EQ(ResolveAlignMode(TimeAlignMode::kOffset, half, true), TimeAlignMode::kOffset);
}

TEST(AlignClocks, ACommonClockThatDisagreesWithTheMotionIsAFinding) {
  const ClockSpans spans{
      .imu_begin_s = 0, .imu_end_s = 100, .ref_begin_s = 0, .ref_end_s = 100};
  TimeAlignment time;
  time.motion_offset_s = 18.2;
  std::vector<VerifyFinding> findings;
  AlignClocks(spans, VerifyOptions{}, {}, time, findings);
  EXPECT_EQ(time.method, TimeAlignMode::kCommonClock);
  EXPECT_EQ(time.offset_s, 0.0);
  ASSERT_EQ(findings.size(), 1u);
  EXPECT_EQ(findings[0].kind, VerifyFindingKind::kClockDisagreement);
  EXPECT_DOUBLE_EQ(findings[0].motion_offset_s, 18.2);
  EXPECT_THAT(findings[0].what, HasSubstr("18 s is GPS time minus UTC"));
  ASSERT_EQ(findings[0].advice.settings.size(), 2u);
  EXPECT_EQ(findings[0].advice.settings[0].option, Option::kTimeAlign);
  EXPECT_EQ(findings[0].advice.settings[0].value, "motion");
  EXPECT_EQ(findings[0].advice.settings[1].option, Option::kTimeOffset);
  // Within kClockDisagreementS: no finding.
  time.motion_offset_s = 1.5;
  findings.clear();
  AlignClocks(spans, VerifyOptions{}, {}, time, findings);
  EXPECT_TRUE(findings.empty());
}

TEST(AlignClocks, TooShortAnOverlapIsATimeErrorWithAdvice) {
  const ClockSpans spans{
      .imu_begin_s = 0, .imu_end_s = 100, .ref_begin_s = 97, .ref_end_s = 200};
  VerifyOptions options;
  options.time_align = TimeAlignMode::kCommonClock;
  TimeAlignment time;
  std::vector<VerifyFinding> findings;
  try {
    AlignClocks(spans, options, {}, time, findings);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kTime);
    EXPECT_THAT(e.what(), HasSubstr("do not overlap in time"));
    EXPECT_THAT(e.what(), HasSubstr("0.000 .. 100.000 s"));
    ASSERT_EQ(e.advice().settings.size(), 2u);
    EXPECT_EQ(e.advice().settings[0].option, Option::kTimeAlign);
  }
  // The offset moves the log onto the reference clock.
  options.time_align = TimeAlignMode::kOffset;
  options.time_offset_s = 90.0;
  AlignClocks(spans, options, {}, time, findings);
  EXPECT_DOUBLE_EQ(time.overlap_start_s, 97.0);
  EXPECT_DOUBLE_EQ(time.overlap_end_s, 190.0);
}

TEST(AlignClocks, MotionAlignmentWithoutAStartNamesTheLog) {
  const ClockSpans spans{
      .imu_begin_s = 0, .imu_end_s = 100, .ref_begin_s = 0, .ref_end_s = 100};
  VerifyOptions options;
  options.time_align = TimeAlignMode::kMotionStart;
  TimeAlignment time;
  std::vector<VerifyFinding> findings;
  MotionStartMissing missing;
  missing.imu_has_no_rest = true;
  missing.imu_source = "walk.csv";
  try {
    AlignClocks(spans, options, missing, time, findings);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("walk.csv does not start at rest"));
    ASSERT_EQ(e.advice().settings.size(), 1u);
    EXPECT_EQ(e.advice().settings[0].option, Option::kTimeOffset);
  }
}

TEST(ReferenceMotionStart, TheLastEpochAtRestBeforeTheDeparture) {
  const TimedPath walk = WalkEast(1000.0, 5.0, 20.0);
  const std::optional<double> start = ReferenceMotionStart(walk);
  ASSERT_TRUE(start);
  // At rest until 1005 s; 0.05 m (the floor of the rest band) is 0.05 s later.
  EXPECT_NEAR(*start, 1005.0, 0.051);
  TimedPath still = walk;
  for (auto& p : still.position_m) p.setZero();
  EXPECT_FALSE(ReferenceMotionStart(still));
}

TEST(HeadingTime, TheFirstEpochFarEnoughFromTheStart) {
  const TimedPath walk = WalkEast(0.0, 2.0, 10.0);
  const std::optional<double> t = HeadingTime(walk, 4.95);
  ASSERT_TRUE(t);
  EXPECT_NEAR(*t, 7.0, 1e-9);
  EXPECT_FALSE(HeadingTime(walk, 50.0));
}

TEST(AddWalkFindings, NoStopInTheMiddleAndAnUnusedGyroscope) {
  StillResult still;
  still.intervals = {{0, 100}, {900, 1000}};  // the rests at the ends only
  std::vector<VerifyFinding> findings;
  AddWalkFindings(still, 1000, true, false, findings);
  ASSERT_EQ(findings.size(), 2u);
  EXPECT_EQ(findings[0].kind, VerifyFindingKind::kNoStop);
  EXPECT_EQ(findings[1].kind, VerifyFindingKind::kGyroscopeUnused);
  still.intervals.insert(still.intervals.begin() + 1, {400, 450});
  findings.clear();
  AddWalkFindings(still, 1000, true, true, findings);
  EXPECT_TRUE(findings.empty());
}

TEST(TrajectoryPreconditions, NoPositionFromAnEmptyPathNorLengthWithoutAStep) {
  const TimedPath empty;
  EXPECT_THROW(empty.At(1.0), Error);
  const TimedPath walk = WalkEast(0.0, 0.0, 10.0);
  EXPECT_NEAR(HorizontalPathLength(walk.position_m, 0.25), 10.0, 1e-9);
  EXPECT_THROW(HorizontalPathLength(walk.position_m, std::nan("")), Error);
  EXPECT_THROW(HorizontalPathLength(walk.position_m, -1.0), Error);
}

}  // namespace
}  // namespace mpcal::internal
