// The steps of the repeatability statistics (repeat_steps.h).
#include "repeat_steps.h"

#include <cmath>
#include <string_view>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "mpcal/distributions.h"
#include "mpcal/error.h"

namespace mpcal::internal {
namespace {

// Relative difference of nominal factors below which two trials are taken to
// share one: only the last digits of a printed double may differ.
constexpr double kSameFactorRelative = 1e-12;

}  // namespace

std::string TrialLabel(std::span<const std::string> names, std::size_t i) {
  if (names.empty() || names[i].empty() || names[i] == fmt::format("trial {}", i + 1)) {
    return fmt::format("trial {}", i + 1);
  }
  return fmt::format("trial {} ({})", i + 1, names[i]);
}

namespace {

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

// What makes trials compare: every session calibrated with the same setting
// (any of `settings`, the first trial's value where there is one).
Advice SameCalibration(std::vector<Setting> settings) {
  Advice advice;
  advice.settings = std::move(settings);
  advice.stage = Stage::kCalibrate;
  return advice;
}

}  // namespace

void CheckTrialsCompare(std::span<const Calibration> trials,
                        std::span<const std::string> names,
                        const RepeatabilityOptions& options) {
  const std::size_t n = trials.size();
  const Calibration& first = trials[0];
  for (std::size_t i = 1; i < n; ++i) {
    const Calibration& c = trials[i];
    if (c.model_kind != first.model_kind) {
      throw Error(
          ErrorKind::kSession,
          fmt::format("{} was calibrated with the model {}, {} with {}: trials "
                      "must share one model",
                      TrialLabel(names, i),
                      ToString(c.model_kind),
                      TrialLabel(names, 0),
                      ToString(first.model_kind)),
          SameCalibration({{Option::kModel, std::string(ToString(first.model_kind))}}));
    }
    if (!(std::abs(c.gravity_mps2 - first.gravity_mps2) <=
          options.gravity_tolerance_mps2)) {
      throw Error(
          ErrorKind::kSession,
          fmt::format(
              "{} was calibrated against gravity {} m/s2, {} against {} m/s2: a "
              "different "
              "gravity shifts the scale-factor errors, so the trials do not compare",
              TrialLabel(names, i),
              c.gravity_mps2,
              TrialLabel(names, 0),
              first.gravity_mps2),
          SameCalibration({{Option::kGravity, fmt::format("{}", first.gravity_mps2)},
                           {Option::kLatitude, ""},
                           {Option::kHeight, ""}}));
    }
    if (c.input_units != first.input_units) {
      throw Error(
          ErrorKind::kSession,
          fmt::format(
              "{} is for input units {}, {} for {}: trials must share the units of their "
              "logs",
              TrialLabel(names, i),
              ToString(c.input_units),
              TrialLabel(names, 0),
              ToString(first.input_units)),
          SameCalibration(
              {{Option::kLogUnits, std::string(ToString(first.input_units))}}));
    }
  }
}

TrialValues CommonFactorValues(std::span<const Calibration> trials,
                               std::span<const std::string> names,
                               std::vector<std::string>& notes) {
  const std::size_t n = trials.size();
  const Calibration& first = trials[0];
  TrialValues out;
  std::vector<Vector9>& values = out.values;
  std::vector<std::optional<Vector9>>& stds = out.stds;
  values.resize(n);
  stds.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const Calibration& c = trials[i];
    values[i] = ToVector(c.model);
    if (c.std) stds[i] = ToVector(*c.std);
    if (!values[i].allFinite() || (stds[i] && !stds[i]->allFinite()) ||
        !std::isfinite(c.mps2_per_unit) || !(c.mps2_per_unit > 0.0)) {
      throw Error(
          ErrorKind::kInput,
          fmt::format(
              "{} has a non-finite parameter, 1σ or nominal factor: it is not a usable "
              "calibration",
              TrialLabel(names, i)));
    }
    if (std::abs(c.mps2_per_unit - first.mps2_per_unit) >
        kSameFactorRelative * first.mps2_per_unit) {
      Reexpress(c.mps2_per_unit, first.mps2_per_unit, values[i], stds[i]);
      notes.push_back(fmt::format(
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
  if (without_std.size() == 1 && n > 1) {
    notes.push_back(fmt::format(
        "{} carries no 1σ (a calibration from another tool): every other trial is "
        "compared with it in units of its own 1σ (z in the last column with two trials)",
        without_std.front()));
  } else if (!without_std.empty() && without_std.size() < n) {
    notes.push_back(
        fmt::format("{} {} no 1σ: no verdict on whether the spread exceeds the noise",
                    fmt::join(without_std, ", "),
                    without_std.size() == 1 ? "carries" : "carry"));
  }

  return out;
}

void SetSpread(const std::vector<double>& values, ParameterRepeatability& out) {
  const auto n = static_cast<double>(values.size());
  out.values = values;
  // Sum the offsets from the first trial: exact when the trials agree (the
  // paper's angles), and no cancellation when they nearly do.
  double offsets = 0.0;
  for (double v : values) offsets += v - values[0];
  out.mean = values[0] + offsets / n;
  double squares = 0.0;
  for (double v : values) squares += (v - out.mean) * (v - out.mean);
  out.std_population = std::sqrt(squares / n);
  out.std_sample = std::sqrt(squares / (n - 1.0));
}

// The verdict against the one trial without 1σ: each other trial's
// difference from it over its own 1σ.
void SetVerdictAgainstReference(double significance,
                                std::size_t reference,
                                ParameterRepeatability& out) {
  const std::size_t n = out.values.size();
  out.reference_trial = reference;
  out.z_from_reference.assign(n, 0.0);
  double chi2 = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    if (i == reference) continue;
    const double z = (out.values[i] - out.values[reference]) / out.trial_std[i];
    out.z_from_reference[i] = z;
    chi2 += z * z;
  }
  out.chi2 = chi2;
  out.p_value = ChiSquareUpperTail(chi2, static_cast<int>(n) - 1);
  out.changed = *out.p_value < significance;
}

void SetVerdict(double significance, ParameterRepeatability& out) {
  const std::size_t n = out.values.size();
  for (std::size_t i = 0; i < n; ++i) {
    if (out.trial_std[i] == 0.0) {
      SetVerdictAgainstReference(significance, i, out);
      return;
    }
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
  out.changed = *out.p_value < significance;
}

}  // namespace mpcal::internal
