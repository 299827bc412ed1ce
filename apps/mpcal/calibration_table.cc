#include "calibration_table.h"

#include <cmath>
#include <cstdio>

#include <fmt/format.h>

#include "colour.h"
#include "mpcal/count.h"
#include "mpcal/noise.h"
#include "mpcal/noise_units.h"

namespace mpcal::cli {
namespace {

struct Row {
  const char* label;
  const char* unit;
  double per_si;  // display units per SI unit
};

// The packed order of kParameterNames.
constexpr Row kRows[9] = {
    {"bias x", "mg", 1e3 / kStandardGravityMps2},
    {"bias y", "mg", 1e3 / kStandardGravityMps2},
    {"bias z", "mg", 1e3 / kStandardGravityMps2},
    {"scale-factor error x", "ppm", 1e6},
    {"scale-factor error y", "ppm", 1e6},
    {"scale-factor error z", "ppm", 1e6},
    {"non-orthogonality yz", "mrad", 1e3},
    {"non-orthogonality zx", "mrad", 1e3},
    {"non-orthogonality zy", "mrad", 1e3},
};

// The short names of the split-half lines, in the packed order.
constexpr const char* kShortNames[9] = {
    "bias x", "bias y", "bias z", "scale x", "scale y", "scale z", "θyz", "θzx", "θzy"};

// One line per split: the halves' positions, the RMS z and the z of each
// parameter, and the verdict of the chi-square test.
std::string FormatSplitHalf(const SplitHalfSummary& check) {
  std::string out;
  for (const SplitHalfComparison& c : check.comparisons) {
    const char* kind = c.kind == SplitKind::kByTime ? "by time" : "alternate positions";
    if (!c.determined) {
      out += fmt::format(
          "split-half ({}, {} + {} positions): not possible, a half needs {} "
          "more than the parameters and must determine them all\n",
          kind,
          c.positions_first,
          c.positions_second,
          Count(SplitRedundancyNeeded(c.kind), "position"));
      continue;
    }
    out += fmt::format(
        "split-half ({}, {} + {} positions): RMS z {:.2f} (honest 1σ: 1 ± {:.2f}); ",
        kind,
        c.positions_first,
        c.positions_second,
        c.rms_z,
        1.0 / std::sqrt(2.0 * c.dof));
    const double per_split = PerSplitSignificance(check.comparisons, check.significance);
    out += c.disagree ? fmt::format(
                            "the halves DISAGREE beyond chance (chi-square p = {:.2g} < "
                            "{:g}, the check's {:g} shared by {:g} splits)\n",
                            c.p_value,
                            per_split,
                            check.significance,
                            check.significance / per_split)
                      : fmt::format("consistent (chi-square p = {:.2g})\n", c.p_value);
    out += "  z:";
    for (std::size_t i = 0; i < c.z.size() && i < 9; ++i) {
      out += fmt::format(
          " {} {:+.2f}{}", kShortNames[i], c.z[i], i + 1 < c.z.size() ? "," : "");
    }
    out += "\n";
  }
  if (check.widening > 1.0) {
    out += fmt::format(
        "every 1σ above is widened by {:.2f} (sqrt(chi-square/dof) of the halves "
        "that disagree)\n",
        check.widening);
  }
  return out;
}

}  // namespace

std::string FormatParameterTable(const Calibration& calibration,
                                 const std::vector<ExtraColumn>& extra,
                                 bool details) {
  const auto value = ToVector(calibration.model);
  const std::optional<Eigen::Matrix<double, 9, 1>> sigma =
      calibration.std ? std::optional(ToVector(*calibration.std)) : std::nullopt;
  const int rows = ParameterCount(calibration.model_kind);
  std::string out = fmt::format("{:<22} {:>12} {:>10}", "parameter", "estimate", "±1σ");
  for (const auto& column : extra) out += fmt::format(" {:>12}", column.title);
  out += fmt::format("  {:<5} {:>22}\n", "unit", "(bias in m/s2)");
  for (int i = 0; i < rows; ++i) {
    const Row& r = kRows[i];
    out += fmt::format("{:<22} {:>12.3f} {:>10}",
                       r.label,
                       value[i] * r.per_si,
                       sigma ? fmt::format("{:.3f}", (*sigma)[i] * r.per_si) : "no 1σ");
    for (const auto& column : extra) {
      out += fmt::format(" {:>12.3f}", column.values_si[i] * r.per_si);
    }
    out += fmt::format("  {:<5}", r.unit);
    if (i < 3) {
      out += sigma ? fmt::format(" {:>10.5f} ± {:.5f}", value[i], (*sigma)[i])
                   : fmt::format(" {:>10.5f}", value[i]);
    }
    out += "\n";
  }
  if (calibration.bias_drift) {
    const BiasDrift& d = *calibration.bias_drift;
    // mg per minute: the unit a warm-up drift reads naturally in.
    const double per = 60.0 * 1e3 / kStandardGravityMps2;
    out += fmt::format(
        "bias drift x, y, z: {:+.4f} ± {:.4f}, {:+.4f} ± {:.4f}, {:+.4f} ± {:.4f} mg/min "
        "(p = {:.2g}); the bias above is the bias at t = {:.1f} s, the middle of "
        "the positions\n",
        d.mps2_per_s.x() * per,
        d.std_mps2_per_s.x() * per,
        d.mps2_per_s.y() * per,
        d.std_mps2_per_s.y() * per,
        d.mps2_per_s.z() * per,
        d.std_mps2_per_s.z() * per,
        d.p_value,
        d.reference_time_s);
  }
  if (details && calibration.input_units == AccelUnits::kCounts) {
    out += fmt::format(
        "readings in counts, scaled by the nominal {:.6g} m/s2 per count "
        "(bias x, y, z = {:.1f}, {:.1f}, {:.1f} counts)\n",
        calibration.mps2_per_unit,
        calibration.model.bias_mps2.x() / calibration.mps2_per_unit,
        calibration.model.bias_mps2.y() / calibration.mps2_per_unit,
        calibration.model.bias_mps2.z() / calibration.mps2_per_unit);
  }
  return out;
}

std::string FormatFitSummary(const CalibrateResult& result) {
  const auto& d = result.detection;
  const auto& s = result.solve;
  std::string out = fmt::format("static positions: {} used", result.positions.size());
  if (d.dropped_short > 0) out += fmt::format(", {} too short dropped", d.dropped_short);
  if (d.merged > 0) out += fmt::format(", {} merged across a bump", d.merged);
  out += fmt::format(
      "\nfit: {} after {} iterations; |a|-g RMS over the positions {:.4f} m/s2 "
      "before, {:.6f} m/s2 after",
      ToString(s.status),
      s.iterations,
      s.residual_rms_before_mps2,
      s.residual_rms_after_mps2);
  if (!s.cross_validation_residual_mps2.empty()) {
    out += fmt::format(" ({:.6f} m/s2 left out, cross-validated)",
                       s.cross_validation_rms_mps2);
  }
  out += fmt::format(
      "\nquality: variance factor {:.3g} (1 = residuals as the sensor noise explains)",
      s.variance_factor);
  if (s.position_scatter_mps2 > 0.0) {
    out += fmt::format(
        "; positions scatter {:.2g} m/s2 beyond the sensor noise (hand tremor, "
        "non-white noise or model error), weighted in",
        s.position_scatter_mps2);
  }
  out += "\n";
  if (const auto n = WhiteNoiseFromPositions(result.calibration.positions)) {
    out += fmt::format(
        "white noise (scatter within the positions): x {:.3g}, y {:.3g}, z {:.3g} "
        "m/s2/√Hz ({:.0f}, {:.0f}, {:.0f} µg/√Hz; 'mpcal noise' on a still "
        "recording for all the terms)\n",
        n->x(),
        n->y(),
        n->z(),
        noise_units::MicroGPerRtHz(n->x()),
        noise_units::MicroGPerRtHz(n->y()),
        noise_units::MicroGPerRtHz(n->z()));
  }
  if (s.bias_drift_p_value && !s.bias_drift) {
    out += fmt::format("bias drift: not significant (p = {:.2g}); the bias is constant\n",
                       *s.bias_drift_p_value);
  }
  if (s.split_half) out += FormatSplitHalf(*s.split_half);
  if (!s.converged()) out += fmt::format("solver: {}\n", s.message);
  return out;
}

namespace {
// Warnings wait until the command has succeeded: a command that fails says
// so in one line (main folds the first warning into it).
std::vector<std::string>& HeldWarnings() {
  static std::vector<std::string> held;
  return held;
}
}  // namespace

void PrintWarnings(const std::vector<std::string>& warnings) {
  HeldWarnings().insert(HeldWarnings().end(), warnings.begin(), warnings.end());
}

std::vector<std::string> TakeHeldWarnings() {
  std::vector<std::string> out;
  out.swap(HeldWarnings());
  return out;
}

void FlushWarnings() {
  std::fflush(stdout);
  const std::string prefix = Paint(stderr, "mpcal: warning:", Tint::kLookAt);
  for (const auto& w : TakeHeldWarnings()) fmt::print(stderr, "{} {}\n", prefix, w);
}

}  // namespace mpcal::cli
