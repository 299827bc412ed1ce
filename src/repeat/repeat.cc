// Repeatability statistics across sessions (Souza & Machado 2016, Tables 4-6).
#include "mpcal/repeat.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>
#include <string_view>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "mpcal/error.h"

namespace mpcal {
namespace {

// Relative difference of nominal factors below which two trials are taken to
// share one: only the last digits of a printed double may differ.
constexpr double kSameFactorRelative = 1e-12;

std::string TrialLabel(std::span<const std::string> names, std::size_t i) {
  if (names.empty() || names[i].empty() || names[i] == fmt::format("trial {}", i + 1)) {
    return fmt::format("trial {}", i + 1);
  }
  return fmt::format("trial {} ({})", i + 1, names[i]);
}

using Vector9 = Eigen::Matrix<double, kNumModelParameters, 1>;

// A calibration re-expressed on the nominal factor `to_factor`: the
// same correction a = T·diag(1/(1+s))·(Y·m − b) written for m = `to_factor`, so
// that trials of raw counts whose nominal factor was found separately in
// each session compare parameter by parameter.
void Reexpress(double from_factor,
               double to_factor,
               Vector9& value,
               std::optional<Vector9>& std) {
  const double k = to_factor / from_factor;
  for (int a = 0; a < 3; ++a) {
    value[a] *= k;
    value[3 + a] = (1.0 + value[3 + a]) * k - 1.0;
    if (std) {
      (*std)[a] *= k;
      (*std)[3 + a] *= k;
    }
  }
}

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

double ChiSquareUpperTail(double chi2, int dof) {
  assert(dof >= 1 && chi2 >= 0.0);
  // Regularised upper incomplete gamma Q(dof/2, chi2/2) in closed form: a
  // finite Poisson sum for even dof, erfc plus half-integer terms for odd dof.
  const double y = chi2 / 2.0;
  const double e = std::exp(-y);
  if (dof % 2 == 0) {
    double term = e;  // y^0/0! e^{-y}
    double sum = term;
    for (int j = 1; j < dof / 2; ++j) {
      term *= y / j;
      sum += term;
    }
    return std::min(1.0, sum);
  }
  double sum = std::erfc(std::sqrt(y));
  if (dof >= 3) {
    // y^{j-1/2} / Γ(j+1/2), j = 1: √y / Γ(3/2) = 2√(y/π).
    double term = e * 2.0 * std::sqrt(y / std::numbers::pi);
    sum += term;
    for (int j = 2; j <= (dof - 1) / 2; ++j) {
      term *= y / (j - 0.5);
      sum += term;
    }
  }
  return std::min(1.0, sum);
}

RepeatabilityResult AnalyzeRepeatability(std::span<const Calibration> trials,
                                         const RepeatabilityOptions& options) {
  return AnalyzeRepeatability(trials, std::span<const std::string>(), options);
}

RepeatabilityResult AnalyzeRepeatability(std::span<const Calibration> trials,
                                         std::span<const std::string> names,
                                         const RepeatabilityOptions& options) {
  if (const std::string problem = options.Validate(); !problem.empty()) {
    throw Error("repeatability options: " + problem);
  }
  const std::size_t n = trials.size();
  if (n < 2) {
    throw Error(fmt::format(
        "repeatability needs at least 2 trials (calibrations of one device in "
        "different sessions), got {}: give two or more recordings or calibration files",
        n));
  }
  if (!names.empty() && names.size() != n) {
    throw Error(
        fmt::format("repeatability: {} trial names for {} trials", names.size(), n));
  }

  const Calibration& first = trials[0];
  for (std::size_t i = 1; i < n; ++i) {
    const Calibration& c = trials[i];
    if (c.model_kind != first.model_kind) {
      throw Error(fmt::format(
          "{} was calibrated with the model {}, {} with {}: trials must share one "
          "model (calibrate every session with the same --model)",
          TrialLabel(names, i),
          ToString(c.model_kind),
          TrialLabel(names, 0),
          ToString(first.model_kind)));
    }
    if (!(std::abs(c.gravity_mps2 - first.gravity_mps2) <=
          options.gravity_tolerance_mps2)) {
      throw Error(fmt::format(
          "{} was calibrated against gravity {} m/s2, {} against {} m/s2: a different "
          "gravity shifts the scale-factor errors, so the trials do not compare "
          "(calibrate every session with the same --gravity or --latitude/--height)",
          TrialLabel(names, i),
          c.gravity_mps2,
          TrialLabel(names, 0),
          first.gravity_mps2));
    }
    if (c.input_units != first.input_units) {
      throw Error(fmt::format(
          "{} is for input units {}, {} for {}: trials must share the units of their "
          "logs (calibrate every session with the same --units)",
          TrialLabel(names, i),
          ToString(c.input_units),
          TrialLabel(names, 0),
          ToString(first.input_units)));
    }
  }

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

  std::vector<Vector9> values(n);
  std::vector<std::optional<Vector9>> stds(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Calibration& c = trials[i];
    values[i] = ToVector(c.model);
    if (c.std) stds[i] = ToVector(*c.std);
    if (!values[i].allFinite() || (stds[i] && !stds[i]->allFinite()) ||
        !std::isfinite(c.mps2_per_unit) || !(c.mps2_per_unit > 0.0)) {
      throw Error(fmt::format(
          "{} has a non-finite parameter, 1σ or nominal factor: it is not a usable "
          "calibration",
          TrialLabel(names, i)));
    }
    if (std::abs(c.mps2_per_unit - first.mps2_per_unit) >
        kSameFactorRelative * first.mps2_per_unit) {
      Reexpress(c.mps2_per_unit, first.mps2_per_unit, values[i], stds[i]);
      result.notes.push_back(fmt::format(
          "{} had the nominal factor {:.9g} m/s2 per unit; its bias and scale-factor "
          "error "
          "are re-expressed on the first trial's {:.9g} m/s2 per unit (same correction)",
          TrialLabel(names, i),
          c.mps2_per_unit,
          first.mps2_per_unit));
    }
  }
  std::vector<std::string> without_std;
  for (std::size_t i = 0; i < n; ++i) {
    if (!stds[i]) without_std.push_back(TrialLabel(names, i));
  }
  // When none carries a 1σ, every row's no_verdict_reason already says so.
  if (!without_std.empty() && without_std.size() < n) {
    result.notes.push_back(
        fmt::format("{} {} no 1σ: no verdict on whether the spread exceeds the noise",
                    fmt::join(without_std, ", "),
                    without_std.size() == 1 ? "carries" : "carry"));
  }

  const int estimated = ParameterCount(first.model_kind);
  for (int p = 0; p < kNumModelParameters; ++p) {
    ParameterRepeatability& out = result.parameters[static_cast<std::size_t>(p)];
    // Sum the offsets from the first trial: exact when the trials agree (the
    // paper's angles), and no cancellation when they nearly do.
    double offsets = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      out.values.push_back(values[i][p]);
      offsets += values[i][p] - values[0][p];
    }
    out.mean = values[0][p] + offsets / static_cast<double>(n);
    double squares = 0.0;
    for (double v : out.values) squares += (v - out.mean) * (v - out.mean);
    out.std_population = std::sqrt(squares / static_cast<double>(n));
    out.std_sample = std::sqrt(squares / static_cast<double>(n - 1));

    // The 6-parameter model holds the angles at zero: no spread to test.
    if (p >= estimated) {
      out.no_verdict_reason =
          fmt::format("not estimated by the model {}", ToString(first.model_kind));
      continue;
    }
    std::size_t missing = n;
    for (std::size_t i = 0; i < n && missing == n; ++i) {
      if (!stds[i]) missing = i;
    }
    if (missing != n) {
      out.no_verdict_reason = fmt::format("no uncertainty given ({} carries no 1σ)",
                                          TrialLabel(names, missing));
      continue;
    }
    for (std::size_t i = 0; i < n; ++i) out.trial_std.push_back((*stds[i])[p]);
    std::size_t zero = n;
    for (std::size_t i = 0; i < n && zero == n; ++i) {
      if (!(out.trial_std[i] > 0.0)) zero = i;
    }
    if (zero != n) {
      out.no_verdict_reason = fmt::format("no uncertainty given ({}'s 1σ of {} is zero)",
                                          TrialLabel(names, zero),
                                          ParameterWords(p));
      continue;
    }
    double weight_sum = 0.0;
    double weighted = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double w = 1.0 / (out.trial_std[i] * out.trial_std[i]);
      weight_sum += w;
      weighted += w * out.values[i];
    }
    const double weighted_mean = weighted / weight_sum;
    double chi2 = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double r = (out.values[i] - weighted_mean) / out.trial_std[i];
      chi2 += r * r;
    }
    out.chi2 = chi2;
    out.p_value = ChiSquareUpperTail(chi2, static_cast<int>(n) - 1);
    out.changed = *out.p_value < options.significance;
  }
  return result;
}

}  // namespace mpcal
