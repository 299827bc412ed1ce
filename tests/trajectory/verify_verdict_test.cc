#include <gtest/gtest.h>

#include "mpcal/verify.h"

namespace mpcal {
namespace {

VerifyResult Walk(double raw_rms_m, std::optional<double> corrected_rms_m) {
  VerifyResult r;
  r.raw.horizontal_rms_m = raw_rms_m;
  if (corrected_rms_m) {
    r.corrected = PathMetrics{};
    r.corrected->horizontal_rms_m = *corrected_rms_m;
  }
  r.gyro_used = true;
  r.stops = 5;
  r.time.offset_s = 0.25;
  return r;
}

TEST(JudgeVerification, ACloserCorrectedWalkIsGoodAndEveryCheckIsThere) {
  const std::vector<Check> checks = JudgeVerification(Walk(668.9, 6.8));
  ASSERT_EQ(checks.size(), 4u);
  EXPECT_EQ(checks[0].kind, CheckKind::kCorrection);
  EXPECT_EQ(checks[0].finding, CheckFinding::kCorrectedCloser);
  EXPECT_DOUBLE_EQ(checks[0].value, 6.8);
  EXPECT_DOUBLE_EQ(checks[0].limit, 668.9);
  EXPECT_EQ(checks[1].finding, CheckFinding::kClockAgrees);
  EXPECT_DOUBLE_EQ(checks[1].value, 0.25);
  EXPECT_EQ(checks[2].finding, CheckFinding::kStopsFound);
  EXPECT_EQ(checks[2].count, 5);
  EXPECT_EQ(checks[3].finding, CheckFinding::kWalkGyroUsed);
  EXPECT_EQ(Worst(checks), Verdict::kGood);
}

TEST(JudgeVerification, ACorrectedWalkNoCloserIsLookedAt) {
  const std::vector<Check> checks = JudgeVerification(Walk(1.74, 1.77));
  EXPECT_EQ(checks[0].finding, CheckFinding::kCorrectedNotCloser);
  EXPECT_EQ(checks[0].verdict, Verdict::kLookAt);
}

TEST(JudgeVerification, NoCalibrationIsSaid) {
  EXPECT_EQ(JudgeVerification(Walk(341.0, std::nullopt))[0].finding,
            CheckFinding::kNoCalibration);
}

TEST(JudgeVerification, FindingsBecomeChecks) {
  VerifyResult r = Walk(668.9, 6.8);
  r.gyro_used = false;
  VerifyFinding clock;
  clock.kind = VerifyFindingKind::kClockDisagreement;
  clock.motion_offset_s = 18.0;
  VerifyFinding no_stop;
  no_stop.kind = VerifyFindingKind::kNoStop;
  VerifyFinding unused;
  unused.kind = VerifyFindingKind::kGyroscopeUnused;
  r.findings = {clock, no_stop, unused};
  const std::vector<Check> checks = JudgeVerification(r);
  EXPECT_EQ(checks[1].finding, CheckFinding::kClockDisagrees);
  EXPECT_EQ(checks[1].verdict, Verdict::kLookAt);
  EXPECT_DOUBLE_EQ(checks[1].value, 18.0);
  EXPECT_DOUBLE_EQ(checks[1].limit, 0.25);
  EXPECT_EQ(checks[2].finding, CheckFinding::kNoStop);
  EXPECT_EQ(checks[3].finding, CheckFinding::kWalkGyroUnused);
  EXPECT_EQ(Worst(checks), Verdict::kLookAt);
}

TEST(JudgeVerification, ALogWithoutGyroscopeIsSaid) {
  VerifyResult r = Walk(1.0, 0.5);
  r.gyro_used = false;
  EXPECT_EQ(JudgeVerification(r)[3].finding, CheckFinding::kWalkNoGyro);
}

}  // namespace
}  // namespace mpcal
