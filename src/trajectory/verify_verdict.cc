#include <algorithm>

#include "mpcal/verify.h"

namespace mpcal {
namespace {

bool Has(const VerifyResult& result, VerifyFindingKind kind) {
  return std::any_of(result.findings.begin(),
                     result.findings.end(),
                     [kind](const VerifyFinding& f) { return f.kind == kind; });
}

Check CorrectionCheck(const VerifyResult& result) {
  Check c{CheckKind::kCorrection, Verdict::kLookAt, CheckFinding::kNoCalibration};
  if (!result.corrected) return c;
  c.value = result.corrected->horizontal_rms_m;
  c.limit = result.raw.horizontal_rms_m;
  const bool closer = c.value < c.limit;
  c.verdict = closer ? Verdict::kGood : Verdict::kLookAt;
  c.finding = closer ? CheckFinding::kCorrectedCloser : CheckFinding::kCorrectedNotCloser;
  return c;
}

Check ClockCheck(const VerifyResult& result) {
  Check c{CheckKind::kClock, Verdict::kGood, CheckFinding::kClockAgrees};
  c.value = result.time.offset_s;
  for (const VerifyFinding& f : result.findings) {
    if (f.kind != VerifyFindingKind::kClockDisagreement) continue;
    // If the clocks do differ, the walk is compared with the wrong stretch
    // of the reference and every distance is off; the start of motion is
    // itself an estimate, so the user decides.
    c.verdict = Verdict::kLookAt;
    c.finding = CheckFinding::kClockDisagrees;
    c.value = f.motion_offset_s;
    c.limit = result.time.offset_s;
  }
  return c;
}

Check StopsCheck(const VerifyResult& result) {
  Check c{CheckKind::kStops, Verdict::kGood, CheckFinding::kStopsFound};
  c.count = result.stops;
  if (Has(result, VerifyFindingKind::kNoStop)) {
    c.verdict = Verdict::kLookAt;
    c.finding = CheckFinding::kNoStop;
  }
  return c;
}

Check GyroscopeCheck(const VerifyResult& result) {
  Check c{CheckKind::kGyroscope, Verdict::kGood, CheckFinding::kWalkGyroUsed};
  if (result.gyro_used) return c;
  c.finding = Has(result, VerifyFindingKind::kGyroscopeUnused)
                  ? CheckFinding::kWalkGyroUnused
                  : CheckFinding::kWalkNoGyro;
  c.verdict = Verdict::kLookAt;
  return c;
}

}  // namespace

std::vector<Check> JudgeVerification(const VerifyResult& result) {
  return {CorrectionCheck(result),
          ClockCheck(result),
          StopsCheck(result),
          GyroscopeCheck(result)};
}

}  // namespace mpcal
