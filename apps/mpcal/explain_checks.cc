#include "explain_checks.h"

#include <numbers>

#include <fmt/format.h>

#include "colour.h"
#include "explain.h"
#include "mpcal/count.h"

namespace mpcal::cli {

namespace {

// A verification's checks (JudgeVerification).
std::string ExplainWalkCheck(const Check& c) {
  switch (c.finding) {
    case CheckFinding::kCorrectedCloser:
      return fmt::format(
          "the corrected walk is closer to the reference: {:.2f} m RMS against {:.2f} m "
          "raw",
          c.value,
          c.limit);
    case CheckFinding::kCorrectedNotCloser:
      return fmt::format(
          "the corrected walk is no closer to the reference ({:.2f} m RMS against {:.2f} "
          "m raw): this walk does not confirm the calibration; is it this sensor's, "
          "from this power-up?",
          c.value,
          c.limit);
    case CheckFinding::kNoCalibration:
      return "no calibration given (--calib): only the raw walk";
    case CheckFinding::kClockAgrees:
      return fmt::format("the IMU and the reference line up (offset {:.3f} s)", c.value);
    case CheckFinding::kClockDisagrees:
      return fmt::format(
          "the starts of motion suggest an offset of {:.1f} s, not the {:.3f} s used: "
          "the clocks may differ (see the warning)",
          c.value,
          c.limit);
    case CheckFinding::kStopsFound:
      return fmt::format(
          "{} with the end rests: zero-velocity updates during the walk",
          Count(static_cast<std::size_t>(c.count), "still stretch", "still stretches"));
    case CheckFinding::kNoStop:
      return "no stop during the walk: a bias's position error grows with the square "
             "of the walking time; stop for a few seconds now and then";
    case CheckFinding::kWalkGyroUsed:
      return "the gyroscope carried the attitude through the turns";
    case CheckFinding::kWalkGyroUnused:
      return "the log has a gyroscope, left out: the attitude is fixed after the start";
    case CheckFinding::kWalkNoGyro:
      return "no gyroscope in the log: the attitude is fixed after the start, right "
             "only for a walk that does not turn the sensor";
    default:
      break;
  }
  return "";
}

}  // namespace

std::string ExplainCheck(const Check& c) {
  constexpr double kDegPerRad = 180.0 / std::numbers::pi;
  switch (c.finding) {
    case CheckFinding::kFitNotConverged:
      return "the fit did not converge";
    case CheckFinding::kFitWithinNoise:
      return fmt::format(
          "residuals as the sensor noise explains (variance factor {:.3g})", c.value);
    case CheckFinding::kFitBeyondNoise:
      return fmt::format(
          "residuals beyond the sensor noise (variance factor {:.3g}, p = {:.2g}): a "
          "position moved or the model misses something; the 1σ are widened for it",
          c.value,
          c.limit);
    case CheckFinding::kOutliersExcluded:
      return fmt::format(
          "{} excluded as outliers (bumped or not still?), the rest as the noise "
          "explains",
          Count(static_cast<std::size_t>(c.count), "position"));
    case CheckFinding::kPositionsEnough:
      return fmt::format("{} determine every parameter, {:.0f} more than the parameters",
                         Count(static_cast<std::size_t>(c.count), "position"),
                         c.value);
    case CheckFinding::kPositionsNoRedundancy:
      return fmt::format(
          "{}, no more than the parameters: nothing checks the fit; record a few more",
          Count(static_cast<std::size_t>(c.count), "position"));
    case CheckFinding::kPoorlyDetermined:
      return fmt::format(
          "{} poorly determined: add positions that fill the gaps ('mpcal detect -v')",
          Count(static_cast<std::size_t>(c.count), "parameter"));
    case CheckFinding::kDriftNotSignificant:
      return fmt::format("the bias is constant over the session (p = {:.2g})", c.value);
    case CheckFinding::kDriftFitted:
      return fmt::format(
          "the bias drifts (p = {:.2g} < {:g}): fitted, the bias given at the middle; "
          "let the sensor warm up before recording",
          c.value,
          c.limit);
    case CheckFinding::kDriftNotTested:
      return "not tested: too few positions for a drifting bias";
    case CheckFinding::kSplitConsistent:
      return "the two halves of the session agree: the 1σ are honest";
    case CheckFinding::kSplitDisagree:
      return fmt::format(
          "the halves of the session disagree (p = {:.2g} < {:.2g}): a bumped stretch "
          "or a drift; record again",
          c.value,
          c.limit);
    case CheckFinding::kSplitNotPossible:
      return "too few positions to calibrate each half: the 1σ are unchecked";
    case CheckFinding::kUnitsFixed:
      return "the readings' magnitude fits gravity in the units given";
    case CheckFinding::kUnitsCounts:
      return fmt::format("raw counts, 1 g = {:.6g} counts (the nominal scale)", c.value);
    case CheckFinding::kGyroConverged:
      return fmt::format("{} fit to {:.3f} deg RMS (variance factor {:.3g})",
                         Count(static_cast<std::size_t>(c.count), "turn"),
                         c.value * kDegPerRad,
                         c.limit);
    case CheckFinding::kGyroPoorlyDetermined:
      return fmt::format(
          "{} of M poorly determined (1σ up to {:.2g}): add turns, as the warning says",
          Count(static_cast<std::size_t>(c.count), "entry", "entries"),
          c.value);
    case CheckFinding::kGyroNotCalibrated:
      return "not calibrated, not written: the turns do not determine M (see the "
             "warning)";
    case CheckFinding::kGyroNotConverged:
      return "not calibrated, not written: its fit did not converge";
    default:  // a verification's
      return ExplainWalkCheck(c);
  }
  return "";
}

std::string FormatChecks(const std::vector<Check>& checks, std::FILE* stream) {
  std::string out = "checks:\n";
  for (const Check& c : checks) {
    out += fmt::format("  {:<11} {} {}\n",
                       ToString(c.kind),
                       PaintVerdict(stream, c.verdict, 11),
                       ExplainCheck(c));
  }
  return out;
}

}  // namespace mpcal::cli
