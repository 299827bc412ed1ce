#include "gyro_calibration_json.h"

#include <cmath>
#include <limits>
#include <string>

#include <fmt/format.h>

#include <Eigen/LU>

#include "mpcal/error.h"

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

GyroCalibration GyroFromJson(const JsonReader& r, const json& object) {
  const std::string path(kPath);
  if (!object.is_object()) {
    r.Fail(fmt::format(
        "'{}' must be an object, found {}", path, JsonReader::TypeName(object)));
  }
  GyroCalibration g;
  const json& input = r.Object(object, path, "input");
  const std::string ipath = path + ".input";
  const std::string units = r.String(input, ipath, "units");
  const auto parsed = ParseGyroUnits(units);
  if (!parsed) {
    r.Fail(fmt::format(
        "unknown units '{}' in '{}.units' (known: rads, dps, counts)", units, ipath));
  }
  g.input_units = *parsed;
  g.radps_per_unit = r.Number(input, ipath, "radps_per_unit");
  if (!(g.radps_per_unit > 0.0)) {
    r.Fail(fmt::format(
        "'{}.radps_per_unit' must be positive, found {}", ipath, g.radps_per_unit));
  }
  g.m = Matrix(Numbers(r, object, path, "m", 9));
  if (std::abs(g.m.determinant()) < 0.1) {
    r.Fail(fmt::format(
        "'{}.m' is not a gyroscope matrix (determinant {:.3g}; near 1 for any "
        "gyroscope)",
        path,
        g.m.determinant()));
  }
  g.bias_radps = r.Vector(object, path, "bias_radps");
  if (object.contains("g_sensitivity_radps_per_mps2")) {
    g.g_sensitivity_radps_per_mps2 =
        Matrix(Numbers(r, object, path, "g_sensitivity_radps_per_mps2", 9));
  }
  if (object.contains("std")) {
    const json& s = r.Object(object, path, "std");
    if (s.contains("bias_radps"))
      g.bias_std_radps = r.Vector(s, path + ".std", "bias_radps");
  }
  if (object.contains("m_covariance")) {
    const std::vector<double> v = Numbers(r, object, path, "m_covariance", 81);
    Eigen::Matrix<double, 9, 9> c;
    for (int i = 0; i < 81; ++i) c.data()[i] = v[static_cast<std::size_t>(i)];
    g.m_covariance = c;
  }
  if (object.contains("fit")) {
    const json& f = r.Object(object, path, "fit");
    const std::string fpath = path + ".fit";
    GyroFitSummary fit;
    fit.turns = static_cast<int>(r.Integer(f, fpath, "turns", 0));
    fit.residual_rms_before_rad = r.Number(f, fpath, "residual_rms_before_rad");
    fit.residual_rms_after_rad = r.Number(f, fpath, "residual_rms_after_rad");
    fit.iterations = static_cast<int>(r.Integer(f, fpath, "iterations", 0));
    fit.converged = r.Bool(f, fpath, "converged");
    fit.variance_factor = r.Number(f, fpath, "variance_factor");
    fit.noise_std_radps = r.Number(f, fpath, "noise_std_radps");
    fit.sample_period_s = r.Number(f, fpath, "sample_period_s");
    g.fit = fit;
  }
  if (object.contains("position_bias")) {
    const json& ps = object["position_bias"];
    if (!ps.is_array()) {
      r.Fail(fmt::format("'{}.position_bias' must be an array, found {}",
                         path,
                         JsonReader::TypeName(ps)));
    }
    for (std::size_t i = 0; i < ps.size(); ++i) {
      const std::string at = fmt::format("{}.position_bias[{}]", path, i);
      if (!ps[i].is_object()) {
        r.Fail(fmt::format(
            "'{}' must be an object, found {}", at, JsonReader::TypeName(ps[i])));
      }
      g.position_bias.push_back(
          {r.Number(ps[i], at, "t_s"), r.Vector(ps[i], at, "bias_radps")});
    }
  }
  return g;
}

}  // namespace mpcal::internal
