// The named steps of AnalyzeRepeatability (repeat.cc): refuse trials that
// do not compare, bring their values onto one nominal factor, then per
// parameter the spread and the chi-square verdict. Room-private.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mpcal/calibration.h"
#include "mpcal/repeat.h"

namespace mpcal::internal {

using Vector9 = Eigen::Matrix<double, kNumModelParameters, 1>;

/// "trial 2", or "trial 2 (b.json)" when a name other than that is given.
std::string TrialLabel(std::span<const std::string> names, std::size_t i);

/// \throws mpcal::Error (ErrorKind::kSession, Advice: calibrate every
///   session with the same setting) when a trial's model, gravity (beyond
///   options.gravity_tolerance_mps2) or input units differ from the first's.
void CheckTrialsCompare(std::span<const Calibration> trials,
                        std::span<const std::string> names,
                        const RepeatabilityOptions& options);

/// Each trial's parameters and 1σ (nullopt without), re-expressed on the
/// first trial's nominal factor (with a note in `notes` for each trial that
/// was), and a note naming the trials without 1σ when some carry one.
struct TrialValues {
  std::vector<Vector9> values;
  std::vector<std::optional<Vector9>> stds;
};
/// \throws mpcal::Error for a non-finite parameter, 1σ or factor.
TrialValues CommonFactorValues(std::span<const Calibration> trials,
                               std::span<const std::string> names,
                               std::vector<std::string>& notes);

/// The values, their mean (the first plus the mean offset from it: exact
/// when the trials agree) and the population and sample standard deviations.
/// \pre at least 2 values.
void SetSpread(const std::vector<double>& values, ParameterRepeatability& out);

/// The chi-square verdict of out.values around their weighted mean with
/// weights 1/σ², σ = out.trial_std (all > 0): chi2, p_value, and changed
/// when p_value < significance.
void SetVerdict(double significance, ParameterRepeatability& out);

}  // namespace mpcal::internal
