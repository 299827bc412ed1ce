// Coverage's findings as plain sentences for a library user, naming no
// option (the command line words the advice as its flags,
// apps/mpcal/explain_detect.cc).
#include <string>

#include <fmt/format.h>

#include "mpcal/count.h"
#include "mpcal/coverage.h"

namespace mpcal {
namespace {

std::string ModelName(ModelKind model) {
  return model == ModelKind::kShinElSheimy9 ? "the 9-parameter model"
                                            : "the 6-parameter model (bias-scale-6)";
}

std::string JoinNames(const std::vector<std::string>& names) {
  std::string out;
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i > 0) out += i + 1 == names.size() ? " and " : ", ";
    out += names[i];
  }
  return out;
}

char AxisName(int axis) { return static_cast<char>('x' + axis); }

}  // namespace

std::string Describe(const CoverageProblem& p) {
  switch (p.kind) {
    case CoverageProblemKind::kTooFewPositions:
      return fmt::format("session has {} static position{}, {} needs at least {}",
                         p.positions,
                         p.positions == 1 ? "" : "s",
                         ModelName(p.model),
                         p.required_positions);
    case CoverageProblemKind::kTooFewOrientations:
      return fmt::format(
          "the {} are only {}, too few to "
          "determine the {} parameters of {}",
          Count(p.positions, "static position"),
          Count(p.distinct_positions, "distinct orientation"),
          p.parameters,
          ModelName(p.model));
    case CoverageProblemKind::kNotDetermined:
      return fmt::format(
          "the {} ({}) do not determine all {} "
          "parameters of {}: they lie too close to one plane or cone",
          Count(p.positions, "static position"),
          Count(p.distinct_positions, "distinct orientation"),
          p.parameters,
          ModelName(p.model));
    case CoverageProblemKind::kBelowRecommended:
      return fmt::format(
          "{}; the paper recommends more than 18 spanning the "
          "sphere",
          Count(p.distinct_positions, "distinct orientation"));
    case CoverageProblemKind::kExactFit:
      return "six positions for six parameters fit exactly: nothing checks the fit (a "
             "seventh position would)";
    case CoverageProblemKind::kNeverUp:
      return fmt::format(
          "+{} never pointed up (closest {:.0f} deg)", AxisName(p.axis), p.angle_deg);
    case CoverageProblemKind::kNeverDown:
      return fmt::format(
          "+{} never pointed down (closest {:.0f} deg)", AxisName(p.axis), p.angle_deg);
    case CoverageProblemKind::kWeak:
      return fmt::format(
          "the positions determine some parameters poorly (observability {:.3g})",
          p.observability);
    case CoverageProblemKind::kEmptyCap:
      return fmt::format(
          "no position within {:.0f} deg of the orientation with the {} down",
          p.angle_deg,
          p.down);
  }
  return "";
}

std::string Describe(const CoverageStep& step) {
  switch (step.kind) {
    case CoverageStepKind::kRecordPositions: {
      const std::string hold = fmt::format("~{:g} s each, still", step.hold_s);
      if (step.orientations.empty()) {
        return fmt::format("record {} in new orientations ({})",
                           Count(step.count, "more position", "more positions"),
                           hold);
      }
      std::vector<std::string> names = step.orientations;
      if (step.unnamed > 0) names.push_back(fmt::format("{} more", step.unnamed));
      return fmt::format("record {} more position{}, e.g. with the {} down ({})",
                         step.count,
                         step.count == 1 ? "" : "s",
                         JoinNames(names),
                         hold);
    }
    case CoverageStepKind::kSixParameterModel:
      return "or calibrate bias and scale only with the 6-parameter model "
             "(six-position protocol: each axis up and down)";
    case CoverageStepKind::kHoldLonger:
      return fmt::format(
          "{} still stretch{} shorter than the minimum static time {} dropped: hold "
          "each position longer",
          step.dropped_short,
          step.dropped_short == 1 ? "" : "es",
          step.dropped_short == 1 ? "was" : "were");
  }
  return "";
}

std::string Summary(const CoverageResult& res,
                    const std::function<std::string(const CoverageStep&)>& word_step) {
  switch (res.verdict) {
    case CoverageVerdict::kNotEnough: {
      std::string out =
          res.problems.empty() ? "not enough" : Describe(res.problems.front());
      for (std::size_t k = 0; k < res.advice.size(); ++k) {
        out += (k == 0 ? ": " : "; ") + word_step(res.advice[k]);
      }
      return out;
    }
    case CoverageVerdict::kUsableWithWarnings:
      return fmt::format("usable with warnings: {}; to improve, {}",
                         res.problems.empty() ? "" : Describe(res.problems.front()),
                         res.advice.empty() ? "record more orientations"
                                            : word_step(res.advice.front()));
    case CoverageVerdict::kGood:
      return fmt::format(
          "good: {} static positions ({} distinct), {} of 26 cube directions covered, "
          "every axis near up and near down",
          res.positions,
          res.distinct_positions,
          res.covered.size());
  }
  return "";
}

std::string Summary(const CoverageResult& result) {
  return Summary(result, [](const CoverageStep& step) { return Describe(step); });
}

}  // namespace mpcal
