/// \file repeat.h
/// \brief Repeatability across sessions: the statistics of the paper's
/// Tables 4-6 (Souza & Machado 2016, §6; docs/method.md §4) over two or more
/// calibrations of one device, and the verdict whether each parameter changed
/// between sessions beyond the trials' own 1σ.
///
/// Per parameter (the 9 of model.h, order of kParameterNames) it gives the
/// per-trial values, the mean, the population standard deviation (÷n, the
/// paper's "desvio padrão") and the sample standard deviation (÷(n−1)).
///
/// The verdict is a chi-square test of the trial values x_i around their
/// weighted mean x̄ = Σ w_i x_i / Σ w_i, w_i = 1/σ_i², with σ_i the trial's 1σ
/// (Calibration::std):
///
///     χ² = Σ w_i (x_i − x̄)²,   n − 1 degrees of freedom,
///
/// and the parameter "changed between sessions" when the probability of a χ²
/// this large from noise alone, P(χ²_{n−1} ≥ χ²), is below the significance
/// level (default 1 %). When a trial carries no 1σ (the paper's printed values,
/// a truth file) there is no verdict ("no uncertainty given"), never a guess.
///
/// Everything is SI, as in the calibration file: bias in m/s², scale-factor
/// error dimensionless, angles in rad. The paper's units (g, ppm) appear only
/// in FormatRepeatabilityTable. The table's files (JSON, CSV) are read and
/// written in mpcal/repeatability_file.h.
#pragma once

#include <array>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "mpcal/calibration.h"
#include "mpcal/distributions.h"  // ChiSquareUpperTail, the test of the verdict
#include "mpcal/model.h"
#include "mpcal/units.h"

namespace mpcal {

struct RepeatabilityOptions {
  /// Significance level of the chi-square test: a parameter is flagged as
  /// changed when noise alone would give a spread this large with probability
  /// below this. 0.01 flags a stable parameter wrongly once in 100; raise it to
  /// catch smaller changes at the cost of more false alarms. In (0, 1).
  double significance = 0.01;
  /// Largest difference of the trials' gravity magnitudes (m/s²) still taken
  /// as the same gravity; beyond it the trials are refused. Only rounding in
  /// a file should differ: keep it tiny.
  double gravity_tolerance_mps2 = 1e-6;

  /// Empty string when valid, otherwise names the first bad field.
  std::string Validate() const;
};

/// One scalar parameter across the trials.
struct ParameterRepeatability {
  /// The value of each trial, in trial order (SI).
  std::vector<double> values;
  /// Each trial's 1σ (SI); empty when there is no verdict. 0 for the
  /// reference trial (below).
  std::vector<double> trial_std;
  /// When exactly one trial carries no 1σ (a calibration imported from
  /// another tool) and every other does: that trial, the one the others are
  /// compared with, and each trial's difference from it in units of the
  /// trial's own 1σ, (value − reference)/1σ (0 for the reference). The
  /// verdict's χ² is then the sum of their squares, n−1 degrees of freedom.
  std::optional<std::size_t> reference_trial;
  std::vector<double> z_from_reference;
  double mean = 0.0;
  /// √(Σ(x−mean)²/n): the paper's "desvio padrão".
  double std_population = 0.0;
  /// √(Σ(x−mean)²/(n−1)).
  double std_sample = 0.0;
  /// True when the spread exceeds the trials' 1σ at the significance level;
  /// nullopt when there is no verdict (see `no_verdict_reason`).
  std::optional<bool> changed;
  /// χ² of the values around their weighted mean (n−1 degrees of freedom)
  /// and its upper-tail probability; nullopt without a verdict or when read
  /// back from JSON (the file does not hold them).
  std::optional<double> chi2;
  std::optional<double> p_value;
  /// Why `changed` is nullopt, in words ("no uncertainty given", "not
  /// estimated by the model bias-scale-6"); empty when there is a verdict.
  std::string no_verdict_reason;
};

/// The repeatability table.
struct RepeatabilityResult {
  int trials = 0;
  /// Names of the trials (file names), for the table; "trial 1", ... when
  /// none were given. Not stored in the JSON.
  std::vector<std::string> trial_names;
  /// The conditions shared by every trial (refused otherwise). Not stored in
  /// the JSON; defaults when read back.
  ModelKind model_kind = ModelKind::kShinElSheimy9;
  double gravity_mps2 = kStandardGravityMps2;
  AccelUnits input_units = AccelUnits::kMps2;
  /// Factor the statistics are expressed on (the first trial's): for raw
  /// counts, trials whose nominal factor differs are re-expressed on it.
  double mps2_per_unit = 1.0;
  /// The significance level the verdicts used.
  double significance = 0.01;
  /// In the order of kParameterNames: bias x, y, z (m/s²), scale-factor
  /// error x, y, z, θyz, θzx, θzy (rad).
  std::array<ParameterRepeatability, kNumModelParameters> parameters;
  /// Findings the user should read with the table (trials re-expressed on a
  /// common nominal factor, trials without 1σ, ...).
  std::vector<std::string> notes;
};

/// The repeatability statistics of `trials`, one calibration per session of
/// the same device. `names` (optional, one per trial) label the trials in
/// messages and the table.
/// \throws mpcal::Error for fewer than 2 trials, `names` of the wrong length,
///   invalid options, a non-finite value, or trials whose model, gravity or
///   input units differ (the message names the trial and what differs).
RepeatabilityResult AnalyzeRepeatability(std::span<const Calibration> trials,
                                         std::span<const std::string> names,
                                         const RepeatabilityOptions& options = {});
/// As above with trials named "trial 1", "trial 2", ...
RepeatabilityResult AnalyzeRepeatability(std::span<const Calibration> trials,
                                         const RepeatabilityOptions& options = {});

/// The paper's table in the paper's units: one column per trial, then mean,
/// "std (n)" and "std (n-1)", the RMS of the trials' own 1σ ("1σ (rms)", "-"
/// without), rows bias (g), scale-factor error (ppm), non-orthogonality (rad),
/// and a last column with the verdict per row (CHANGED / no change with the
/// p-value, "no 1σ given", "not estimated"). Trial names other than "trial N"
/// are listed above the table.
std::string FormatRepeatabilityTable(const RepeatabilityResult& result);

/// The verdict in plain words (a few lines): which parameters changed between
/// sessions beyond their 1σ and which did not, and what that means for when to
/// calibrate.
std::string RepeatabilityVerdict(const RepeatabilityResult& result);

}  // namespace mpcal
