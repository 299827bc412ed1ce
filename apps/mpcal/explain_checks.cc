#include "explain_checks.h"

#include <numbers>

#include <fmt/format.h>

#include "colour.h"
#include "explain.h"
#include "mpcal/count.h"

namespace mpcal::cli {

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
