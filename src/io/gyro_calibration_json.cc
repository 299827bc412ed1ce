#include "gyro_calibration_json.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <utility>

#include <fmt/format.h>

#include <Eigen/LU>

#include "mpcal/error.h"
#include "mpcal/plausible.h"

namespace mpcal::internal {
namespace {

using json = JsonReader::json;

constexpr std::string_view kPath = "gyroscope";

double Finite(double v, const std::string& field) {
  if (!std::isfinite(v)) {
    throw Error(fmt::format(
        "cannot write the calibration: '{}.{}' is {} (not finite)", kPath, field, v));
  }
  return v;
}

json Array(const double* v, int n, const std::string& field) {
  json a = json::array();
  for (int i = 0; i < n; ++i) a.push_back(Finite(v[i], field));
  return a;
}

json Vec3(const Eigen::Vector3d& v, const std::string& field) {
  return Array(v.data(), 3, field);
}

json RowMajor(const Eigen::Matrix3d& m, const std::string& field) {
  double v[9];
  for (int i = 0; i < 9; ++i) v[i] = m(i / 3, i % 3);
  return Array(v, 9, field);
}

// `size` finite numbers at `key` of `object`.
std::vector<double> Numbers(const JsonReader& r,
                            const json& object,
                            const std::string& path,
                            std::string_view key,
                            std::size_t size) {
  const std::string field = JsonReader::Join(path, key);
  const json& a = r.ArrayValue(r.Field(object, path, key), field, size);
  std::vector<double> v;
  for (std::size_t i = 0; i < size; ++i) {
    v.push_back(r.NumberValue(a[i], fmt::format("{}[{}]", field, i)));
  }
  return v;
}

Eigen::Matrix3d Matrix(const std::vector<double>& v) {
  Eigen::Matrix3d m;
  for (int i = 0; i < 9; ++i) m(i / 3, i % 3) = v[static_cast<std::size_t>(i)];
  return m;
}

// rad/s per unit: fixed for rad/s and deg/s; for raw counts a sensor's
// sensitivity (plausible.h).
void CheckNominalScale(const JsonReader& r,
                       const GyroCalibration& g,
                       const std::string& units) {
  const std::string field = std::string(kPath) + ".input.radps_per_unit";
  if (const auto fixed = FixedRadpsPerUnit(g.input_units)) {
    if (!(std::abs(g.radps_per_unit - *fixed) <= 1e-9 * *fixed)) {
      r.Fail(fmt::format("'{}' is {} but units '{}' mean {} rad/s per unit",
                         field,
                         g.radps_per_unit,
                         units,
                         *fixed));
    }
    return;
  }
  if (!(g.radps_per_unit >= 1.0 / kMaxCountsPerRadps &&
        g.radps_per_unit <= 1.0 / kMinCountsPerRadps)) {
    r.Fail(fmt::format(
        "'{}' = {} is not a gyroscope's scale (between {:g} and {:g} counts per rad/s)",
        field,
        g.radps_per_unit,
        kMinCountsPerRadps,
        kMaxCountsPerRadps));
  }
}

// The plausible ranges of plausible.h applied to the fields of one block:
// a value outside them is a corrupt file, not a sensor, and would be applied
// as it is (an M of 1e308 writes rates of 1e305 rad/s).
struct Ranges {
  const JsonReader& r;
  const GyroCalibration& g;

  // The largest bias: the full scale in rad/s; the ADC's range for counts.
  double MaxBias() const {
    return g.input_units == GyroUnits::kCounts ? kMaxReadingCounts * g.radps_per_unit
                                               : kMaxGyroBiasRadps;
  }
  // `spread`: a 1σ or a max - min, not negative; the latter spans up to
  // twice the largest bias.
  void Bias(const Eigen::Vector3d& v, const std::string& field, bool spread) const {
    const double limit = spread ? 2.0 * MaxBias() : MaxBias();
    for (int i = 0; i < 3; ++i) {
      if (spread && !(v[i] >= 0.0)) {
        r.Fail(fmt::format(
            "'{}.{}[{}]' = {} is negative (a spread or a 1σ)", kPath, field, i, v[i]));
      }
      if (!(std::abs(v[i]) <= limit)) {
        r.Fail(fmt::format(
            "'{}.{}[{}]' = {} rad/s is beyond any gyroscope's bias (±{:.4g} rad/s{})",
            kPath,
            field,
            i,
            v[i],
            limit,
            g.input_units == GyroUnits::kCounts ? ", the ADC's range"
                                                : ", 4000 °/s full scale"));
      }
    }
  }
  void M(const Eigen::Matrix3d& m, const std::string& field) const {
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) {
        const double v = m(i, j);
        if (i == j && !(std::abs(v - 1.0) < kMaxScaleFactorError)) {
          r.Fail(fmt::format(
              "'{}.{}[{}]' = {} is not a scale 1 + s with |s| < {:g}: the axis would "
              "read {:.3g} times the true rate",
              kPath,
              field,
              3 * i + j,
              v,
              kMaxScaleFactorError,
              v));
        }
        if (i != j && !(std::abs(v) < kMaxGyroMisalignment)) {
          r.Fail(fmt::format(
              "'{}.{}[{}]' = {} is not a small angle (a misalignment, |m| < {:g} rad)",
              kPath,
              field,
              3 * i + j,
              v,
              kMaxGyroMisalignment));
        }
      }
    }
  }
  void MStd(const Eigen::Matrix3d& s) const {
    for (int i = 0; i < 9; ++i) {
      const double v = s(i / 3, i % 3);
      if (!(v >= 0.0 && v < kMaxScaleFactorError)) {
        r.Fail(fmt::format("'{}.std.m[{}]' = {} is not a 1σ of M (0 to {:g})",
                           kPath,
                           i,
                           v,
                           kMaxScaleFactorError));
      }
    }
  }
  void Covariance(const Eigen::Matrix<double, 9, 9>& c) const {
    const double max_variance = kMaxScaleFactorError * kMaxScaleFactorError;
    for (int i = 0; i < 9; ++i) {
      if (!(c(i, i) >= 0.0 && c(i, i) < max_variance)) {
        r.Fail(
            fmt::format("'{}.m_covariance[{}]' = {} is not a variance of M (0 to {:g})",
                        kPath,
                        10 * i,
                        c(i, i),
                        max_variance));
      }
    }
    for (int i = 0; i < 9; ++i) {
      for (int j = 0; j < 9; ++j) {
        // A correlation beyond 1 (with room for rounding) or an asymmetric
        // matrix is not a covariance.
        const double bound = std::sqrt(c(i, i) * c(j, j)) * (1.0 + 1e-6) + 1e-300;
        if (!(std::abs(c(i, j)) <= bound) ||
            !(std::abs(c(i, j) - c(j, i)) <= 1e-6 * bound)) {
          r.Fail(
              fmt::format("'{}.m_covariance[{}]' = {} is not a covariance (its "
                          "correlation is beyond 1, or the matrix is not symmetric)",
                          kPath,
                          9 * i + j,
                          c(i, j)));
        }
      }
    }
  }
  void GSensitivity(const Eigen::Matrix3d& gs) const {
    for (int i = 0; i < 9; ++i) {
      const double v = gs(i / 3, i % 3);
      if (!(std::abs(v) <= kMaxGyroGSensitivityRadpsPerMps2)) {
        r.Fail(fmt::format(
            "'{}.g_sensitivity_radps_per_mps2[{}]' = {} is beyond any gyroscope's "
            "g-sensitivity (±{:.3g} rad/s per m/s², 10 °/s per g)",
            kPath,
            i,
            v,
            kMaxGyroGSensitivityRadpsPerMps2));
      }
    }
  }
};

// `"gyroscope.fit"`: counts, angles and noise as a fit can give them.
GyroFitSummary ReadFit(const JsonReader& r, const json& f) {
  const std::string fpath = std::string(kPath) + ".fit";
  GyroFitSummary fit;
  fit.turns = static_cast<int>(r.Integer(f, fpath, "turns", 0));
  fit.residual_rms_before_rad = r.Number(f, fpath, "residual_rms_before_rad");
  fit.residual_rms_after_rad = r.Number(f, fpath, "residual_rms_after_rad");
  fit.iterations = static_cast<int>(r.Integer(f, fpath, "iterations", 0));
  fit.converged = r.Bool(f, fpath, "converged");
  fit.variance_factor = r.Number(f, fpath, "variance_factor");
  fit.noise_std_radps = r.Number(f, fpath, "noise_std_radps");
  fit.sample_period_s = r.Number(f, fpath, "sample_period_s");
  // A tilt lies in [0, π]; an RMS of tilts too.
  for (auto [name, v] :
       {std::pair{"residual_rms_before_rad", fit.residual_rms_before_rad},
        std::pair{"residual_rms_after_rad", fit.residual_rms_after_rad}}) {
    if (!(v >= 0.0 && v <= std::numbers::pi)) {
      r.Fail(
          fmt::format("'{}.{}' = {} is not an angle between 0 and pi", fpath, name, v));
    }
  }
  if (!(fit.variance_factor >= 0.0 && fit.variance_factor <= 1e12)) {
    r.Fail(
        fmt::format("'{}.variance_factor' = {} is not a ratio of chi-square to its "
                    "degrees of freedom (0 to 1e12)",
                    fpath,
                    fit.variance_factor));
  }
  if (!(fit.noise_std_radps >= 0.0 && fit.noise_std_radps <= kMaxGyroRateRadps)) {
    r.Fail(
        fmt::format("'{}.noise_std_radps' = {} is not a gyroscope's noise (0 to {:.4g} "
                    "rad/s)",
                    fpath,
                    fit.noise_std_radps,
                    kMaxGyroRateRadps));
  }
  if (!(fit.sample_period_s == 0.0 || (fit.sample_period_s >= kMinSamplePeriodS &&
                                       fit.sample_period_s <= kMaxSamplePeriodS))) {
    r.Fail(
        fmt::format("'{}.sample_period_s' = {} is not a sample period ({:g} to {:g} s)",
                    fpath,
                    fit.sample_period_s,
                    kMinSamplePeriodS,
                    kMaxSamplePeriodS));
  }
  return fit;
}

}  // namespace

json GyroToJson(const GyroCalibration& g) {
  json j;
  j["input"] = {{"units", std::string(ToString(g.input_units))},
                {"radps_per_unit", Finite(g.radps_per_unit, "input.radps_per_unit")}};
  j["m"] = RowMajor(g.m, "m");
  j["bias_radps"] = Vec3(g.bias_radps, "bias_radps");
  j["bias_change_radps"] = Vec3(g.BiasChangeRadps(), "bias_change_radps");
  if (g.g_sensitivity_radps_per_mps2) {
    j["g_sensitivity_radps_per_mps2"] =
        RowMajor(*g.g_sensitivity_radps_per_mps2, "g_sensitivity_radps_per_mps2");
  }
  if (g.m_covariance) {
    json s;
    s["m"] = RowMajor(g.MStd(), "std.m");
    if (g.bias_std_radps) s["bias_radps"] = Vec3(*g.bias_std_radps, "std.bias_radps");
    j["std"] = s;
    j["m_covariance"] = Array(g.m_covariance->data(), 81, "m_covariance");
  }
  if (g.fit) {
    const GyroFitSummary& f = *g.fit;
    j["fit"] = {{"turns", f.turns},
                {"residual_rms_before_rad",
                 Finite(f.residual_rms_before_rad, "fit.residual_rms_before_rad")},
                {"residual_rms_after_rad",
                 Finite(f.residual_rms_after_rad, "fit.residual_rms_after_rad")},
                {"iterations", f.iterations},
                {"converged", f.converged},
                {"variance_factor", Finite(f.variance_factor, "fit.variance_factor")},
                {"noise_std_radps", Finite(f.noise_std_radps, "fit.noise_std_radps")},
                {"sample_period_s", Finite(f.sample_period_s, "fit.sample_period_s")}};
  }
  json positions = json::array();
  for (const GyroBiasSample& b : g.position_bias) {
    positions.push_back({{"t_s", Finite(b.t_s, "position_bias.t_s")},
                         {"bias_radps", Vec3(b.bias_radps, "position_bias.bias_radps")}});
  }
  j["position_bias"] = std::move(positions);
  return j;
}

namespace {

// `"gyroscope.input"`: the units and their nominal scale.
void ReadInput(const JsonReader& r, const json& object, GyroCalibration& g) {
  const std::string ipath = std::string(kPath) + ".input";
  const json& input = r.Object(object, std::string(kPath), "input");
  const std::string units = r.String(input, ipath, "units");
  const auto parsed = ParseGyroUnits(units);
  if (!parsed) {
    r.Fail(fmt::format(
        "unknown units '{}' in '{}.units' (known: rads, dps, counts)", units, ipath));
  }
  g.input_units = *parsed;
  g.radps_per_unit = r.Number(input, ipath, "radps_per_unit");
  CheckNominalScale(r, g, units);
}

// `"gyroscope.std"` and `"gyroscope.m_covariance"`.
void ReadUncertainty(const Ranges& ranges, const json& object, GyroCalibration& g) {
  const JsonReader& r = ranges.r;
  const std::string path(kPath);
  if (object.contains("std")) {
    const json& s = r.Object(object, path, "std");
    if (s.contains("bias_radps")) {
      g.bias_std_radps = r.Vector(s, path + ".std", "bias_radps");
      ranges.Bias(*g.bias_std_radps, "std.bias_radps", true);
    }
    if (s.contains("m")) ranges.MStd(Matrix(Numbers(r, s, path + ".std", "m", 9)));
  }
  if (object.contains("m_covariance")) {
    const std::vector<double> v = Numbers(r, object, path, "m_covariance", 81);
    Eigen::Matrix<double, 9, 9> c;
    for (int i = 0; i < 81; ++i) c.data()[i] = v[static_cast<std::size_t>(i)];
    ranges.Covariance(c);
    g.m_covariance = c;
  }
}

// `"gyroscope.position_bias"`: times on a logger's clock, plausible biases.
void ReadPositionBias(const Ranges& ranges, const json& ps, GyroCalibration& g) {
  const JsonReader& r = ranges.r;
  const std::string path(kPath);
  if (!ps.is_array()) {
    r.Fail(fmt::format(
        "'{}.position_bias' must be an array, found {}", path, JsonReader::TypeName(ps)));
  }
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const std::string at = fmt::format("{}.position_bias[{}]", path, i);
    if (!ps[i].is_object()) {
      r.Fail(fmt::format(
          "'{}' must be an object, found {}", at, JsonReader::TypeName(ps[i])));
    }
    const GyroBiasSample b{r.Number(ps[i], at, "t_s"), r.Vector(ps[i], at, "bias_radps")};
    if (!(std::abs(b.t_s) <= kMaxTimeS)) {
      r.Fail(fmt::format("'{}.t_s' = {:.6g} s is beyond any logger's clock", at, b.t_s));
    }
    ranges.Bias(b.bias_radps, fmt::format("position_bias[{}].bias_radps", i), false);
    g.position_bias.push_back(b);
  }
}

}  // namespace

GyroCalibration GyroFromJson(const JsonReader& r, const json& object) {
  const std::string path(kPath);
  if (!object.is_object()) {
    r.Fail(fmt::format(
        "'{}' must be an object, found {}", path, JsonReader::TypeName(object)));
  }
  GyroCalibration g;
  ReadInput(r, object, g);
  const Ranges ranges{r, g};
  g.m = Matrix(Numbers(r, object, path, "m", 9));
  ranges.M(g.m, "m");
  if (std::abs(g.m.determinant()) < 0.1) {
    r.Fail(fmt::format(
        "'{}.m' is not a gyroscope matrix (determinant {:.3g}; near 1 for any "
        "gyroscope)",
        path,
        g.m.determinant()));
  }
  g.bias_radps = r.Vector(object, path, "bias_radps");
  ranges.Bias(g.bias_radps, "bias_radps", false);
  if (object.contains("bias_change_radps")) {
    ranges.Bias(r.Vector(object, path, "bias_change_radps"), "bias_change_radps", true);
  }
  if (object.contains("g_sensitivity_radps_per_mps2")) {
    g.g_sensitivity_radps_per_mps2 =
        Matrix(Numbers(r, object, path, "g_sensitivity_radps_per_mps2", 9));
    ranges.GSensitivity(*g.g_sensitivity_radps_per_mps2);
  }
  ReadUncertainty(ranges, object, g);
  if (object.contains("fit")) {
    g.fit = ReadFit(r, r.Object(object, path, "fit"));
    // Only a converged fit is written: a block that says otherwise is not a
    // calibration to apply.
    if (!g.fit->converged) {
      r.Fail(
          fmt::format("'{}.fit.converged' is false: the block is not a calibration "
                      "of the gyroscope",
                      path));
    }
  }
  if (object.contains("position_bias"))
    ReadPositionBias(ranges, object["position_bias"], g);
  return g;
}

}  // namespace mpcal::internal
