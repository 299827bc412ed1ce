#include "gyro_table.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>
#include <utility>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "mpcal/repeat.h"

namespace mpcal::cli {
namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;
constexpr const char* kAxis = "xyz";

std::string Row(const std::string& label,
                double value,
                std::optional<double> sigma,
                std::optional<double> extra,
                const char* unit) {
  std::string out = fmt::format("{:<22} {:>12.3f} {:>10}",
                                label,
                                value,
                                sigma ? fmt::format("{:.3f}", *sigma) : "no 1σ");
  if (extra) out += fmt::format(" {:>12.3f}", *extra);
  return out + fmt::format("  {}\n", unit);
}

}  // namespace

std::string FormatGyroTable(const GyroCalibration& g,
                            const GyroCalibration* extra,
                            const std::string& extra_title,
                            bool details) {
  const bool has_std = g.m_covariance.has_value();
  const Eigen::Matrix3d s = g.MStd();
  std::string out = fmt::format("{:<22} {:>12} {:>10}", "gyroscope", "estimate", "±1σ");
  if (extra) out += fmt::format(" {:>12}", extra_title);
  out += "  unit   (ω = M (raw − b))\n";
  auto opt = [&](double v) { return has_std ? std::optional(v) : std::nullopt; };
  auto ext = [&](double v) { return extra ? std::optional(v) : std::nullopt; };
  for (int i = 0; i < 3; ++i) {
    out += Row(fmt::format("scale-factor error {}", kAxis[i]),
               (g.m(i, i) - 1.0) * 1e6,
               opt(s(i, i) * 1e6),
               extra ? ext((extra->m(i, i) - 1.0) * 1e6) : std::nullopt,
               "ppm");
  }
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      if (r == c) continue;
      out += Row(fmt::format("misalignment m_{}{}", kAxis[r], kAxis[c]),
                 g.m(r, c) * 1e3,
                 opt(s(r, c) * 1e3),
                 extra ? ext(extra->m(r, c) * 1e3) : std::nullopt,
                 "mrad");
    }
  }
  const Eigen::Vector3d change = g.BiasChangeRadps();
  for (int i = 0; i < 3; ++i) {
    out += Row(fmt::format("bias {} (mean)", kAxis[i]),
               g.bias_radps[i] * kDegPerRad,
               g.bias_std_radps ? std::optional((*g.bias_std_radps)[i] * kDegPerRad)
                                : std::nullopt,
               extra ? ext(extra->bias_radps[i] * kDegPerRad) : std::nullopt,
               "deg/s");
  }
  if (details && !g.position_bias.empty()) {
    out += fmt::format(
        "bias measured at {} positions; its change over the session (max - min) x, y, z "
        "= "
        "{:.4f}, {:.4f}, {:.4f} deg/s\n",
        g.position_bias.size(),
        change.x() * kDegPerRad,
        change.y() * kDegPerRad,
        change.z() * kDegPerRad);
  }
  if (g.g_sensitivity_radps_per_mps2) {
    // deg/s per g, rows x, y, z.
    const Eigen::Matrix3d gs =
        *g.g_sensitivity_radps_per_mps2 * kDegPerRad * kStandardGravityMps2;
    out += fmt::format(
        "bias g-sensitivity G (deg/s per g; bias = b + G f, the bias above without G f): "
        "[{:.4f} {:.4f} {:.4f}; {:.4f} {:.4f} {:.4f}; {:.4f} {:.4f} {:.4f}]\n",
        gs(0, 0),
        gs(0, 1),
        gs(0, 2),
        gs(1, 0),
        gs(1, 1),
        gs(1, 2),
        gs(2, 0),
        gs(2, 1),
        gs(2, 2));
  }
  if (details && g.input_units == GyroUnits::kCounts) {
    out += fmt::format(
        "gyroscope readings in counts, scaled by the nominal {:.6g} rad/s per count "
        "(bias x, "
        "y, z = {:.1f}, {:.1f}, {:.1f} counts)\n",
        g.radps_per_unit,
        g.bias_radps.x() / g.radps_per_unit,
        g.bias_radps.y() / g.radps_per_unit,
        g.bias_radps.z() / g.radps_per_unit);
  }
  return out;
}

std::string FormatGyroSummary(const GyroResult& r) {
  std::string out =
      fmt::format("gyroscope: {} turns between the positions", r.turns.size());
  if (!r.calibration.fit) return out + fmt::format("; {}\n", ToString(r.status));
  const GyroFitSummary& f = *r.calibration.fit;
  out += fmt::format(
      "; {} after {} iterations; gravity carried over each turn vs measured after it, "
      "tilt "
      "RMS {:.3f} deg before (nominal scale, bias at every position), {:.3f} deg after\n",
      ToString(r.status),
      f.iterations,
      f.residual_rms_before_rad * kDegPerRad,
      f.residual_rms_after_rad * kDegPerRad);
  out += fmt::format(
      "gyroscope quality: variance factor {:.3g} (1 = turn residuals as the gyroscope "
      "and "
      "accelerometer noise explain); noise at rest {:.3g} deg/s per sample; bias "
      "g-sensitivity {} (F = {:.3g})\n",
      f.variance_factor,
      f.noise_std_radps * kDegPerRad,
      r.calibration.g_sensitivity_radps_per_mps2 ? "modelled" : "not modelled",
      r.g_sensitivity_f);
  const GyroDirections& d = r.directions;
  if (d.carry_noise_rad > 0.0) {
    out += fmt::format(
        "gyroscope directions: {} (the hand's sway there {:.3f} deg, the gyroscope's "
        "noise over the window {:.3f} deg)\n",
        d.carried ? "each sample of the window next to a turn carried to its edge by the "
                    "gyroscope"
                  : "the accelerometer's plain mean over the window next to a turn",
        d.sway_rad * kDegPerRad,
        d.carry_noise_rad * kDegPerRad);
  }
  if (!r.converged()) out += fmt::format("gyroscope solver: {}\n", r.message);
  return out;
}

std::vector<std::string> GyroFindingMessages(const GyroResult& r) {
  std::vector<std::string> out;
  if (r.status == GyroStatus::kNoConvergence) {
    out.push_back(fmt::format("gyroscope not calibrated: the fit did not converge ({})",
                              r.message));
  }
  for (const GyroFinding& f : r.findings) {
    std::vector<std::string> names;
    for (int p : f.parameters)
      names.emplace_back(kGyroParameterNames[static_cast<std::size_t>(p)]);
    std::vector<std::string> axes;
    for (int a = 0; a < 3; ++a) {
      if (f.turn_axes[static_cast<std::size_t>(a)]) axes.emplace_back(1, kAxis[a]);
    }
    switch (f.kind) {
      case GyroFindingKind::kTooFewTurns:
        out.push_back(fmt::format(
            "gyroscope not calibrated: {:.0f} turns between static positions give {:.0f} "
            "equations for the 9 entries of M; record at least {:.0f} turns, about the "
            "x, y "
            "and z axes",
            f.value,
            2 * f.value,
            f.limit));
        break;
      case GyroFindingKind::kUndetermined:
        out.push_back(fmt::format(
            "gyroscope not calibrated: the turns do not determine {} (1σ {:.2g}); add "
            "turns "
            "of 45-90 degrees about the {} axis of the sensor between positions",
            fmt::join(names, ", "),
            f.value,
            fmt::join(axes, " and ")));
        break;
      case GyroFindingKind::kPoorlyDetermined:
        out.push_back(
            fmt::format("gyroscope: {} poorly determined (1σ up to {:.2g}, above "
                        "{:.2g}); add turns about "
                        "the {} axis of the sensor",
                        fmt::join(names, ", "),
                        f.value,
                        f.limit,
                        fmt::join(axes, " and ")));
        break;
    }
  }
  return out;
}

namespace {

// One row of the repeat table: a value and its 1σ per trial, in display
// units.
struct RepeatRow {
  std::string label;
  std::string unit;
  std::vector<double> values;
  std::vector<std::optional<double>> sigmas;  // nullopt: a trial without 1σ
};

// Each trial's nominal scale over the first's. A calibration of raw counts
// finds its own nominal rad/s per count, and M is relative to it: the same
// gyroscope gives M = 1.003 at one nominal scale and 0.998 at another 0.5 %
// larger. The trials are compared at the first one's nominal scale: M k / k₁
// and the bias in counts times k₁.
std::vector<double> NominalRatios(const std::vector<const GyroCalibration*>& g) {
  std::vector<double> ratios;
  for (const GyroCalibration* t : g) {
    const bool counts = t->input_units == GyroUnits::kCounts &&
                        g.front()->input_units == GyroUnits::kCounts &&
                        t->radps_per_unit > 0.0 && g.front()->radps_per_unit > 0.0;
    ratios.push_back(counts ? t->radps_per_unit / g.front()->radps_per_unit : 1.0);
  }
  return ratios;
}

// `ratios`: NominalRatios(g).
std::vector<RepeatRow> GyroRepeatRows(const std::vector<const GyroCalibration*>& g,
                                      const std::vector<double>& ratios) {
  std::vector<RepeatRow> rows;
  for (int p = 0; p < 9; ++p) {
    const int r = p / 3;
    const int c = p % 3;
    RepeatRow row;
    row.label = r == c ? fmt::format("scale-factor error {}", kAxis[r])
                       : fmt::format("misalignment m_{}{}", kAxis[r], kAxis[c]);
    row.unit = r == c ? "ppm" : "mrad";
    const double factor = r == c ? 1e6 : 1e3;
    for (std::size_t i = 0; i < g.size(); ++i) {
      const GyroCalibration& t = *g[i];
      row.values.push_back((t.m(r, c) * ratios[i] - (r == c ? 1.0 : 0.0)) * factor);
      row.sigmas.push_back(t.m_covariance
                               ? std::optional(t.MStd()(r, c) * ratios[i] * factor)
                               : std::nullopt);
    }
    rows.push_back(row);
  }
  for (int i = 0; i < 3; ++i) {
    RepeatRow row{fmt::format("bias {} (mean)", kAxis[i]), "deg/s", {}, {}};
    for (std::size_t j = 0; j < g.size(); ++j) {
      const GyroCalibration& t = *g[j];
      row.values.push_back(t.bias_radps[i] / ratios[j] * kDegPerRad);
      row.sigmas.push_back(t.bias_std_radps ? std::optional((*t.bias_std_radps)[i] /
                                                            ratios[j] * kDegPerRad)
                                            : std::nullopt);
    }
    rows.push_back(row);
  }
  return rows;
}

// Sample std, and the chi-square p-value of the trials against their
// weighted mean (negative when a trial has no 1σ). With exactly one trial
// without 1σ (a calibration from another tool), the others are compared with
// it in units of their own 1σ, as repeat does for the accelerometer.
struct GyroSpread {
  double sample_std = 0.0;
  double p = -1.0;
  std::optional<double> z;  // two trials, one without 1σ: the other's z
};
GyroSpread Spread(const RepeatRow& row) {
  const auto n = static_cast<double>(row.values.size());
  double mean = 0.0;
  for (double v : row.values) mean += v / n;
  double ss = 0.0;
  for (double v : row.values) ss += (v - mean) * (v - mean);
  const double sample_std = std::sqrt(ss / (n - 1.0));
  const auto without = static_cast<std::size_t>(
      std::count(row.sigmas.begin(), row.sigmas.end(), std::nullopt));
  if (without > 1) return {sample_std, -1.0, std::nullopt};
  if (without == 1) {
    const std::size_t ref = static_cast<std::size_t>(
        std::find(row.sigmas.begin(), row.sigmas.end(), std::nullopt) -
        row.sigmas.begin());
    double chi2 = 0.0;
    std::optional<double> z;
    for (std::size_t i = 0; i < row.values.size(); ++i) {
      if (i == ref) continue;
      const double zi = (row.values[i] - row.values[ref]) / *row.sigmas[i];
      chi2 += zi * zi;
      if (row.values.size() == 2) z = zi;
    }
    return {sample_std, ChiSquareUpperTail(chi2, static_cast<int>(n) - 1), z};
  }
  double w_sum = 0.0;
  double wx = 0.0;
  for (std::size_t i = 0; i < row.values.size(); ++i) {
    const double w = 1.0 / (*row.sigmas[i] * *row.sigmas[i]);
    w_sum += w;
    wx += w * row.values[i];
  }
  double chi2 = 0.0;
  for (std::size_t i = 0; i < row.values.size(); ++i) {
    chi2 += std::pow((row.values[i] - wx / w_sum) / *row.sigmas[i], 2);
  }
  return {sample_std,
          ChiSquareUpperTail(chi2, static_cast<int>(row.values.size()) - 1),
          std::nullopt};
}

}  // namespace

std::string FormatGyroRepeatTable(std::span<const Calibration> trials,
                                  std::span<const std::string> names) {
  std::vector<const GyroCalibration*> g;
  std::vector<std::string> used;
  for (std::size_t i = 0; i < trials.size(); ++i) {
    if (!trials[i].gyroscope) continue;
    g.push_back(&*trials[i].gyroscope);
    used.push_back(i < names.size() ? names[i] : fmt::format("trial {}", i + 1));
  }
  if (g.size() < 2) return "";
  std::string out =
      fmt::format("\ngyroscope over {} trials (ω = M (raw − b)):\n", g.size());
  const std::vector<double> ratios = NominalRatios(g);
  if (std::any_of(ratios.begin(), ratios.end(), [](double r) { return r != 1.0; })) {
    out += fmt::format(
        "(raw counts: every trial at trial 1's nominal {:.6g} rad/s per count, M times "
        "its own nominal scale over that one, the bias in counts times it)\n",
        g.front()->radps_per_unit);
  }
  out += fmt::format("{:<22} {:<6}", "parameter", "unit");
  for (std::size_t i = 0; i < g.size(); ++i)
    out += fmt::format(" {:>18}", fmt::format("trial {}", i + 1));
  out += fmt::format(" {:>10} {:>10}  {}\n", "mean", "std", "between trials");
  std::vector<std::string> changed;
  bool any_without = false;
  for (const RepeatRow& row : GyroRepeatRows(g, ratios)) {
    out += fmt::format("{:<22} {:<6}", row.label, row.unit);
    for (std::size_t i = 0; i < row.values.size(); ++i) {
      out +=
          row.sigmas[i]
              ? fmt::format(" {:>18}",
                            fmt::format("{:.3f} ± {:.3f}", row.values[i], *row.sigmas[i]))
              : fmt::format(" {:>18}", fmt::format("{:.3f} no 1σ", row.values[i]));
    }
    double mean = 0.0;
    for (double v : row.values) mean += v / static_cast<double>(row.values.size());
    const GyroSpread spread = Spread(row);
    const double p = spread.p;
    const bool differs = p >= 0.0 && p < 0.01;
    if (differs) changed.push_back(row.label);
    if (p < 0.0) any_without = true;
    out += fmt::format(
        " {:>10.3f} {:>10.3f}  {}\n",
        mean,
        spread.sample_std,
        p < 0.0 ? std::string("no 1σ")
                : fmt::format("{}{} (p = {:.2g})",
                              differs ? "changed" : "consistent",
                              spread.z ? fmt::format(" z={:+.2f}", *spread.z) : "",
                              p));
  }
  for (std::size_t i = 0; i < used.size(); ++i)
    out += fmt::format("trial {}: {}\n", i + 1, used[i]);
  if (any_without) {
    out += "gyroscope: no verdict: more than one trial carries no 1σ.\n";
    return out;
  }
  out += changed.empty()
             ? "gyroscope: every entry consistent between the trials within their 1σ "
               "(chi-square, 1 % significance).\n"
             : fmt::format(
                   "gyroscope: changed between the trials beyond their 1σ: {} "
                   "(chi-square, 1 % significance).\n",
                   fmt::join(changed, ", "));
  return out;
}

}  // namespace mpcal::cli
