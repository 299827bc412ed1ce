// Repeatability statistics across sessions (Souza & Machado 2016, Tables 4-6).
#include "mpcal/repeat.h"

#include <algorithm>
#include <cmath>
#include <string_view>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "mpcal/error.h"
#include "repeat_steps.h"

namespace mpcal {
namespace {

using internal::TrialLabel;

std::string_view ParameterWords(int p) {
  static constexpr std::array<std::string_view, kNumModelParameters> kWords = {
      "bias x",
      "bias y",
      "bias z",
      "scale-factor error x",
      "scale-factor error y",
      "scale-factor error z",
      "non-orthogonality yz",
      "non-orthogonality zx",
      "non-orthogonality zy"};
  return kWords[static_cast<std::size_t>(p)];
}

// Why a parameter gets no verdict: not estimated, or a trial without a
// usable 1σ for it; empty when every trial gives one.
std::string NoVerdictReason(int p,
                            ModelKind model,
                            const internal::TrialValues& trials,
                            std::span<const std::string> names) {
  // The 6-parameter model holds the angles at zero: no spread to test.
  if (p >= ParameterCount(model)) {
    return fmt::format("not estimated by the model {}", ToString(model));
  }
  // One trial without 1σ is the reference the others are compared with;
  // two or more leave nothing to compare in units of a 1σ.
  std::size_t without = 0;
  std::size_t first_without = 0;
  for (std::size_t i = 0; i < trials.stds.size(); ++i) {
    if (trials.stds[i]) continue;
    if (without++ == 0) first_without = i;
  }
  if (without > 1) {
    return fmt::format("no uncertainty given ({} carries no 1σ)",
                       TrialLabel(names, first_without));
  }
  for (std::size_t i = 0; i < trials.stds.size(); ++i) {
    if (!trials.stds[i]) continue;
    if (!((*trials.stds[i])[p] > 0.0)) {
      return fmt::format("no uncertainty given ({}'s 1σ of {} is zero)",
                         TrialLabel(names, i),
                         ParameterWords(p));
    }
  }
  return "";
}

}  // namespace

std::string RepeatabilityOptions::Validate() const {
  if (!(significance > 0.0 && significance < 1.0)) {
    return fmt::format("significance must be in (0, 1), got {}", significance);
  }
  if (!(gravity_tolerance_mps2 >= 0.0) || !std::isfinite(gravity_tolerance_mps2)) {
    return fmt::format("gravity_tolerance_mps2 must be finite and >= 0, got {}",
                       gravity_tolerance_mps2);
  }
  return "";
}

RepeatabilityResult AnalyzeRepeatability(std::span<const Calibration> trials,
                                         const RepeatabilityOptions& options) {
  return AnalyzeRepeatability(trials, std::span<const std::string>(), options);
}

RepeatabilityResult AnalyzeRepeatability(std::span<const Calibration> trials,
                                         std::span<const std::string> names,
                                         const RepeatabilityOptions& options) {
  if (const std::string problem = options.Validate(); !problem.empty()) {
    throw Error(ErrorKind::kOption, "repeatability options: " + problem);
  }
  const std::size_t n = trials.size();
  if (n < 2) {
    throw Error(
        ErrorKind::kSession,
        fmt::format(
            "repeatability needs at least 2 trials (calibrations of one device in "
            "different sessions), got {}: give two or more recordings or calibration "
            "files",
            n));
  }
  if (!names.empty() && names.size() != n) {
    throw Error(
        ErrorKind::kOption,
        fmt::format("repeatability: {} trial names for {} trials", names.size(), n));
  }

  internal::CheckTrialsCompare(trials, names, options);
  const Calibration& first = trials[0];
  RepeatabilityResult result;
  result.trials = static_cast<int>(n);
  result.model_kind = first.model_kind;
  result.gravity_mps2 = first.gravity_mps2;
  result.input_units = first.input_units;
  result.mps2_per_unit = first.mps2_per_unit;
  result.significance = options.significance;
  for (std::size_t i = 0; i < n; ++i) {
    result.trial_names.push_back(
        names.empty() || names[i].empty() ? fmt::format("trial {}", i + 1) : names[i]);
  }

  const internal::TrialValues common =
      internal::CommonFactorValues(trials, names, result.notes);
  for (int p = 0; p < kNumModelParameters; ++p) {
    ParameterRepeatability& out = result.parameters[static_cast<std::size_t>(p)];
    std::vector<double> values;
    for (const auto& v : common.values) values.push_back(v[p]);
    internal::SetSpread(values, out);
    out.no_verdict_reason = NoVerdictReason(p, first.model_kind, common, names);
    if (!out.no_verdict_reason.empty()) continue;
    for (const auto& s : common.stds) out.trial_std.push_back(s ? (*s)[p] : 0.0);
    internal::SetVerdict(options.significance, out);
  }
  return result;
}

}  // namespace mpcal
