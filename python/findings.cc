#include "findings.h"

#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "errors.h"
#include "mpcal/gyro.h"
#include "mpcal/solve.h"

namespace mpcal::python {
namespace {

std::string SolveKind(SolveNoteKind kind) {
  switch (kind) {
    case SolveNoteKind::kOutlierExcluded:
      return "outlier_excluded";
    case SolveNoteKind::kOutlierKept:
      return "outlier_kept";
    case SolveNoteKind::kPoorlyDetermined:
      return "poorly_determined";
    case SolveNoteKind::kNoRedundancy:
      return "no_redundancy";
    case SolveNoteKind::kHalvesDisagree:
      return "halves_disagree";
  }
  return "poorly_determined";
}

py::dict SolveFigures(const SolveNote& n) {
  py::dict f;
  switch (n.kind) {
    case SolveNoteKind::kOutlierExcluded:
    case SolveNoteKind::kOutlierKept:
      f["position"] = n.position;
      f["start_s"] = n.start_s;
      f["end_s"] = n.end_s;
      f["residual_z"] = n.residual_z;
      break;
    case SolveNoteKind::kPoorlyDetermined:
      f["parameter"] = n.parameter;
      break;
    case SolveNoteKind::kNoRedundancy:
      f["positions"] = n.positions;
      f["parameters"] = n.parameters;
      break;
    case SolveNoteKind::kHalvesDisagree:
      f["split"] = n.halves.kind == SplitKind::kByTime ? "by_time" : "interleaved";
      f["positions_first"] = n.halves.positions_first;
      f["positions_second"] = n.halves.positions_second;
      f["rms_z"] = n.halves.rms_z;
      f["dof"] = n.halves.dof;
      f["p_value"] = n.halves.p_value;
      f["widening"] = n.widening;
      break;
  }
  return f;
}

// What would help: more positions filling the gaps (detect shows them).
Advice SeeCoverage() {
  Advice advice;
  advice.stage = Stage::kDetect;
  return advice;
}

// The gyroscope's findings in words (the command's sentences, without its
// flags: none of them names one).
std::string GyroMessage(const GyroFinding& f,
                        const std::vector<std::string>& names,
                        const std::vector<std::string>& axes) {
  switch (f.kind) {
    case GyroFindingKind::kTooFewTurns:
      return fmt::format(
          "gyroscope not calibrated: {:.0f} turns between static positions give {:.0f} "
          "equations for the 9 entries of M; record at least {:.0f} turns, about the x, "
          "y and z axes",
          f.value,
          2 * f.value,
          f.limit);
    case GyroFindingKind::kUndetermined:
      return fmt::format(
          "gyroscope not calibrated: the turns do not determine {} (1σ {:.2g}); add "
          "turns of 45-90 degrees about the {} axis of the sensor between positions",
          fmt::join(names, ", "),
          f.value,
          fmt::join(axes, " and "));
    case GyroFindingKind::kPoorlyDetermined:
      return fmt::format(
          "gyroscope: {} poorly determined (1σ up to {:.2g}, above {:.2g}); add turns "
          "about the {} axis of the sensor",
          fmt::join(names, ", "),
          f.value,
          f.limit,
          fmt::join(axes, " and "));
  }
  return "gyroscope: " + fmt::format("{}", fmt::join(names, ", "));
}

void AddGyroFindings(const GyroResult& r, py::list& out) {
  if (r.status == GyroStatus::kNoConvergence) {
    py::dict f;
    out.append(FindingOf(
        "gyroscope_not_converged",
        fmt::format("gyroscope not calibrated: the fit did not converge ({})", r.message),
        Advice{},
        f));
  }
  static constexpr const char* kAxes[] = {"x", "y", "z"};
  for (const GyroFinding& g : r.findings) {
    std::vector<std::string> names;
    for (int p : g.parameters) {
      names.emplace_back(kGyroParameterNames[static_cast<std::size_t>(p)]);
    }
    std::vector<std::string> axes;
    for (std::size_t a = 0; a < 3; ++a) {
      if (g.turn_axes[a]) axes.emplace_back(kAxes[a]);
    }
    py::dict f;
    f["parameters"] = names;
    f["turn_axes"] = axes;
    const char* kind = "gyroscope_too_few_turns";
    if (g.kind == GyroFindingKind::kTooFewTurns) {
      f["turns"] = g.value;
      f["turns_needed"] = g.limit;
    } else {
      kind = g.kind == GyroFindingKind::kUndetermined ? "gyroscope_undetermined"
                                                      : "gyroscope_poorly_determined";
      f["std"] = g.value;
      f["std_limit"] = g.limit;
    }
    out.append(FindingOf(kind, GyroMessage(g, names, axes), Advice{}, f));
  }
}

}  // namespace

py::dict FindingOf(const std::string& kind,
                   const std::string& message,
                   const Advice& advice,
                   py::dict figures) {
  py::dict d;
  d["kind"] = kind;
  d["message"] = message;
  d["advice"] = AdviceSettings(advice);
  d["stage"] = StageOf(advice);
  d["figures"] = std::move(figures);
  return d;
}

py::dict DetectNoteFinding(const DetectNote& n, const std::string& message) {
  py::dict f;
  if (n.kind == DetectNoteKind::kClippedPosition) {
    f["start_s"] = n.start_s;
    f["end_s"] = n.end_s;
    f["clipped_samples"] = n.clipped_samples;
    f["clip_limits"] = n.clip_limits;
    return FindingOf("clipped_position", message, n.advice, f);
  }
  f["quiet_g"] = n.quiet_g;
  f["quiet_quantile"] = n.quiet_quantile;
  f["plausible_quiet_g"] = n.plausible_quiet_g;
  return FindingOf("not_still", message, n.advice, f);
}

py::list CalibrateFindings(const CalibrateResult& result) {
  py::list out;
  const auto& warnings = result.warnings;
  std::size_t k = 0;
  for (const DetectNote& n : result.detection.notes) {
    out.append(DetectNoteFinding(n, k < warnings.size() ? warnings[k] : Describe(n)));
    ++k;
  }
  for (std::size_t j = 0; j < result.solve.notes.size(); ++j, ++k) {
    const SolveNote& n = result.solve.notes[j];
    const std::string& message =
        k < warnings.size() ? warnings[k] : result.solve.warnings.at(j);
    const bool coverage = n.kind == SolveNoteKind::kPoorlyDetermined ||
                          n.kind == SolveNoteKind::kNoRedundancy;
    out.append(FindingOf(SolveKind(n.kind),
                         message,
                         coverage ? SeeCoverage() : Advice{},
                         SolveFigures(n)));
  }
  // The gyroscope that could not be calibrated at all (its error's words).
  for (; k < warnings.size(); ++k) {
    out.append(FindingOf("gyroscope_not_calibrated", warnings[k], Advice{}, py::dict()));
  }
  if (result.gyro) AddGyroFindings(*result.gyro, out);
  return out;
}

}  // namespace mpcal::python
