#include "calibration_table.h"

#include <cmath>
#include <cstdio>

#include <fmt/format.h>

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

}  // namespace

std::string FormatParameterTable(const Calibration& calibration,
                                 const std::vector<ExtraColumn>& extra) {
  const auto value = ToVector(calibration.model);
  const std::optional<Eigen::Matrix<double, 9, 1>> sigma =
      calibration.std ? std::optional(ToVector(*calibration.std)) : std::nullopt;
  const int rows = ParameterCount(calibration.model_kind);
  std::string out = fmt::format("{:<22} {:>12} {:>10}", "parameter", "estimate", "±1σ");
  for (const auto& column : extra) out += fmt::format(" {:>12}", column.title);
  out += fmt::format("  {:<5} {:>22}\n", "unit", "(bias in m/s2)");
  for (int i = 0; i < rows; ++i) {
    const Row& r = kRows[i];
    out += fmt::format("{:<22} {:>12.3f} {:>10}", r.label, value[i] * r.per_si,
                       sigma ? fmt::format("{:.3f}", (*sigma)[i] * r.per_si) : "-");
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
  if (calibration.input_units == AccelUnits::kCounts) {
    out += fmt::format("readings in counts, scaled by the nominal {:.6g} m/s2 per count "
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
  std::string out = fmt::format(
      "static positions: {} used", result.positions.size());
  if (d.dropped_short > 0) out += fmt::format(", {} too short dropped", d.dropped_short);
  if (d.merged > 0) out += fmt::format(", {} merged across a bump", d.merged);
  out += fmt::format("\nfit: {} after {} iterations; |a|-g RMS over the positions {:.4f} m/s2 "
                     "before, {:.6f} m/s2 after",
                     ToString(s.status), s.iterations, s.residual_rms_before_mps2,
                     s.residual_rms_after_mps2);
  if (!s.cross_validation_residual_mps2.empty()) {
    out += fmt::format(" ({:.6f} m/s2 left out, cross-validated)", s.cross_validation_rms_mps2);
  }
  out += fmt::format("\nquality: variance factor {:.3g} (1 = residuals as the sensor noise explains)",
                     s.variance_factor);
  if (s.position_scatter_mps2 > 0.0) {
    out += fmt::format("; positions scatter {:.2g} m/s2 beyond the sensor noise (hand tremor, "
                       "non-white noise or model error), weighted in",
                       s.position_scatter_mps2);
  }
  out += "\n";
  if (const auto n = WhiteNoiseFromPositions(result.calibration.positions)) {
    out += fmt::format("white noise (scatter within the positions): x {:.3g}, y {:.3g}, z {:.3g} "
                       "m/s2/√Hz ({:.0f}, {:.0f}, {:.0f} µg/√Hz; 'mpcal noise' on a still "
                       "recording for all the terms)\n",
                       n->x(), n->y(), n->z(), noise_units::MicroGPerRtHz(n->x()),
                       noise_units::MicroGPerRtHz(n->y()), noise_units::MicroGPerRtHz(n->z()));
  }
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
  for (const auto& w : TakeHeldWarnings()) fmt::print(stderr, "mpcal: warning: {}\n", w);
}

}  // namespace mpcal::cli
