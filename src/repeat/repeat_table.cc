// The repeatability table in the paper's units and the verdict in words.
#include <algorithm>
#include <cmath>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "mpcal/repeat.h"

namespace mpcal {
namespace {

// How a packed parameter is shown: the units of every mpcal table (bias in
// mg, scale-factor error in ppm, angles in mrad) and the precision of a value
// in it.
struct RowStyle {
  std::string_view label;
  std::string_view unit;
  double per_si;  // displayed unit per SI unit
  int decimals;
};

constexpr std::array<RowStyle, kNumModelParameters> kRows = {{
    {"bias x", "mg", 1e3 / kStandardGravityMps2, 3},
    {"bias y", "mg", 1e3 / kStandardGravityMps2, 3},
    {"bias z", "mg", 1e3 / kStandardGravityMps2, 3},
    {"scale error x", "ppm", 1e6, 2},
    {"scale error y", "ppm", 1e6, 2},
    {"scale error z", "ppm", 1e6, 2},
    {"non-orth. yz", "mrad", 1e3, 3},
    {"non-orth. zx", "mrad", 1e3, 3},
    {"non-orth. zy", "mrad", 1e3, 3},
}};

constexpr int kLabelWidth = 14;
constexpr int kUnitWidth = 4;
constexpr int kValueWidth = 12;
constexpr int kStdWidth = 11;

std::string VerdictCell(const ParameterRepeatability& p) {
  if (!p.changed) {
    return p.no_verdict_reason.rfind("not estimated", 0) == 0 ? "not estimated"
                                                              : "no 1σ given";
  }
  // Below 1e-15 the tail is beyond double rounding of the sum that gave it.
  const std::string pv = !p.p_value           ? std::string()
                         : *p.p_value < 1e-15 ? std::string(" (p<1e-15)")
                                              : fmt::format(" (p={:.2g})", *p.p_value);
  // Two trials, one without 1σ: the other's difference in units of its 1σ.
  std::string z;
  if (p.reference_trial && p.values.size() == 2) {
    z = fmt::format(" z={:+.2f}", p.z_from_reference[1 - *p.reference_trial]);
  }
  return (*p.changed ? "CHANGED" : "no change") + z + pv;
}

// "bias x, y, z" / "scale-factor error y" / "non-orthogonality yz, zy": the
// parameters of `indices` grouped by kind.
std::string GroupWords(const std::vector<int>& indices) {
  static constexpr std::array<std::string_view, 3> kGroups = {
      "bias", "scale-factor error", "non-orthogonality"};
  static constexpr std::array<std::string_view, kNumModelParameters> kAxes = {
      "x", "y", "z", "x", "y", "z", "yz", "zx", "zy"};
  std::vector<std::string> parts;
  for (int g = 0; g < 3; ++g) {
    std::string axes;
    for (int p : indices) {
      if (p / 3 != g) continue;
      axes +=
          (axes.empty() ? "" : ", ") + std::string(kAxes[static_cast<std::size_t>(p)]);
    }
    if (!axes.empty()) parts.push_back(fmt::format("{} {}", kGroups[g], axes));
  }
  return fmt::format("{}", fmt::join(parts, "; "));
}

}  // namespace

std::string FormatRepeatabilityTable(const RepeatabilityResult& result) {
  std::string out = fmt::format(
      "Repeatability over {} trials (model {}, gravity {} m/s2, input units {})\n",
      result.trials,
      ToString(result.model_kind),
      result.gravity_mps2,
      ToString(result.input_units));
  for (int t = 0; t < result.trials; ++t) {
    const std::string& name =
        result.trial_names.size() == static_cast<std::size_t>(result.trials)
            ? result.trial_names[static_cast<std::size_t>(t)]
            : std::string();
    if (!name.empty() && name != fmt::format("trial {}", t + 1)) {
      out += fmt::format("  trial {}: {}\n", t + 1, name);
    }
  }
  out += fmt::format(
      "std (n): population standard deviation (divides by n, the paper's \"desvio "
      "padrao\"); std (n-1): sample standard deviation; 1σ (rms): RMS of the trials' own "
      "1σ\n\n");

  out += fmt::format("{:<{}} {:<{}}", "parameter", kLabelWidth, "unit", kUnitWidth);
  for (int t = 0; t < result.trials; ++t) {
    out += fmt::format(" {:>{}}", fmt::format("trial {}", t + 1), kValueWidth);
  }
  out += fmt::format(" {:>{}} {:>{}} {:>{}} {:>{}}  {}\n",
                     "mean",
                     kValueWidth,
                     "std (n)",
                     kStdWidth,
                     "std (n-1)",
                     kStdWidth,
                     "1σ (rms)",
                     kStdWidth,
                     "between sessions");
  for (int p = 0; p < kNumModelParameters; ++p) {
    const RowStyle& style = kRows[static_cast<std::size_t>(p)];
    const ParameterRepeatability& row = result.parameters[static_cast<std::size_t>(p)];
    out += fmt::format("{:<{}} {:<{}}", style.label, kLabelWidth, style.unit, kUnitWidth);
    for (double v : row.values) {
      out += fmt::format(" {:>{}.{}f}", v * style.per_si, kValueWidth, style.decimals);
    }
    // The trials' own 1σ as one figure: the RMS over trials.
    std::string sigma = "no 1σ";
    if (!row.trial_std.empty()) {
      // Over the trials that carry one (the reference trial's is 0).
      double sum = 0.0;
      int with = 0;
      for (double s : row.trial_std) {
        sum += s * s;
        with += s > 0.0 ? 1 : 0;
      }
      sigma = fmt::format("{:.4g}", std::sqrt(sum / std::max(with, 1)) * style.per_si);
    }
    out += fmt::format(" {:>{}.{}f} {:>{}.4g} {:>{}.4g} {:>{}}  {}\n",
                       row.mean * style.per_si,
                       kValueWidth,
                       style.decimals,
                       row.std_population * style.per_si,
                       kStdWidth,
                       row.std_sample * style.per_si,
                       kStdWidth,
                       sigma,
                       kStdWidth,
                       VerdictCell(row));
  }
  return out;
}

namespace {

// The kinds of parameter (scale, non-orthogonality) whose three were all
// tested and held: only those are named (the 6-parameter model has no
// angles; trials without σ give no verdict).
std::vector<std::string> KindsThatHeld(const RepeatabilityResult& result) {
  std::vector<std::string> held;
  for (int kind = 1; kind < 3; ++kind) {
    bool all_held = true;
    for (int p = 3 * kind; p < 3 * kind + 3; ++p) {
      const std::optional<bool>& verdict =
          result.parameters[static_cast<std::size_t>(p)].changed;
      if (!verdict || *verdict) all_held = false;
    }
    if (all_held) held.push_back(kind == 1 ? "scale" : "non-orthogonality");
  }
  return held;
}

}  // namespace

std::string RepeatabilityVerdict(const RepeatabilityResult& result) {
  std::vector<int> changed, stable, unknown;
  bool any_no_sigma = false;
  for (int p = 0; p < kNumModelParameters; ++p) {
    const ParameterRepeatability& row = result.parameters[static_cast<std::size_t>(p)];
    if (row.changed) {
      (*row.changed ? changed : stable).push_back(p);
    } else if (row.no_verdict_reason.rfind("not estimated", 0) != 0) {
      unknown.push_back(p);
      any_no_sigma = true;
    }
  }
  const bool only_bias_changed =
      !changed.empty() && changed.back() < 3;  // indices ascend; bias is 0..2
  std::string out;
  if (!changed.empty()) {
    out +=
        fmt::format("{} changed between sessions beyond their 1σ", GroupWords(changed));
    if (only_bias_changed) out += " — expected: the bias changes at every power-up";
    out += stable.empty() ? ".\n" : fmt::format("; {} did not.\n", GroupWords(stable));
  } else if (!stable.empty()) {
    out += fmt::format("{}: no change between sessions beyond their 1σ.\n",
                       GroupWords(stable));
  }
  if (!unknown.empty()) {
    out += fmt::format(
        "{}: no uncertainty given (a trial carries no 1σ, e.g. values copied from a "
        "paper, or truth files); the standard deviations above are all there is.\n",
        changed.empty() && stable.empty() ? std::string("No verdict on any parameter")
                                          : "No verdict on " + GroupWords(unknown));
  }
  const auto& bias = result.parameters;
  out += fmt::format(
      "Bias spread between sessions, std (n): x {:.3g} mg, y {:.3g} mg, z {:.3g} mg.\n",
      bias[0].std_population / kStandardGravityMps2 * 1e3,
      bias[1].std_population / kStandardGravityMps2 * 1e3,
      bias[2].std_population / kStandardGravityMps2 * 1e3);

  if (only_bias_changed) {
    const std::vector<std::string> held = KindsThatHeld(result);
    out += held.empty()
               ? std::string("So: re-estimate the bias at every power-up.\n")
               : fmt::format(
                     "So: calibrate {} once; re-estimate the bias at every power-up "
                     "(or calibrate before each use).\n",
                     fmt::join(held, " and "));
  } else if (!changed.empty()) {
    out +=
        "So: calibrate before each use, and look for a cause of the change in scale or "
        "non-orthogonality (temperature, a loose mount, too few or poorly spread "
        "positions).\n";
  } else if (!stable.empty() && !any_no_sigma) {
    out +=
        "So: one calibration holds across these sessions; repeat it now and then to "
        "confirm.\n";
  } else if (stable.empty()) {
    out +=
        "So: no verdict; calibrate each session with mpcal (which reports the 1σ of "
        "every parameter) and compare those.\n";
  }
  if (!changed.empty() || !stable.empty()) {
    out += fmt::format(
        "(Chi-square test of each parameter's trial values against the trials' own 1σ, "
        "{:g} % significance.)\n",
        result.significance * 100.0);
  }
  return out;
}

}  // namespace mpcal
