#include "mpcal/calibration_file.h"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <numbers>
#include <sstream>
#include <string_view>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "io/gyro_calibration_json.h"
#include "io/json_reader.h"
#include "mpcal/atomic_file.h"
#include "mpcal/error.h"
#include "mpcal/log_reader.h"
#include "mpcal/plausible.h"
#include "mpcal/text_input.h"

namespace mpcal {
namespace {

// Ordered, so that the file reads top-down as the README documents it:
// format first, then model, gravity, units, parameters, fit, positions.
using json = JsonReader::json;

constexpr std::string_view kFormatFamily = "mpcal.accelerometer";
constexpr int kMajorVersion = 1;
// Earth's gravity, and what a sensor's parameters can be: plausible.h.

// ----- writing -----

void CheckFinite(double v, const std::string& field) {
  if (!std::isfinite(v)) {
    throw Error(
        fmt::format("cannot write the calibration: '{}' is {} (not finite)", field, v));
  }
}

json Vec3(const Eigen::Vector3d& v, const std::string& field) {
  for (int i = 0; i < 3; ++i) CheckFinite(v[i], field);
  return json::array({v.x(), v.y(), v.z()});
}

json Num(double v, const std::string& field) {
  CheckFinite(v, field);
  return v;
}

void PutModel(json& j, const ErrorModel& m, const std::string& prefix) {
  j["bias_mps2"] = Vec3(m.bias_mps2, prefix + "bias_mps2");
  j["scale_factor_error"] = Vec3(m.scale_factor_error, prefix + "scale_factor_error");
  j["non_orthogonality_rad"] = {
      {"yz", Num(m.theta_yz_rad, prefix + "non_orthogonality_rad.yz")},
      {"zx", Num(m.theta_zx_rad, prefix + "non_orthogonality_rad.zx")},
      {"zy", Num(m.theta_zy_rad, prefix + "non_orthogonality_rad.zy")}};
}

// `"fit.split_half"`: one object per split, keyed by its kind.
json SplitHalfJson(const SplitHalfSummary& summary) {
  json j = {{"significance", Num(summary.significance, "fit.split_half.significance")},
            {"widening", Num(summary.widening, "fit.split_half.widening")}};
  for (const SplitHalfComparison& c : summary.comparisons) {
    const std::string at = fmt::format("fit.split_half.{}.", ToString(c.kind));
    json q = {{"positions", json::array({c.positions_first, c.positions_second})},
              {"determined", c.determined}};
    if (c.determined) {
      json z = json::array();
      for (double v : c.z) z.push_back(Num(v, at + "z"));
      q["z"] = std::move(z);
      q["rms_z"] = Num(c.rms_z, at + "rms_z");
      q["chi2"] = Num(c.chi2, at + "chi2");
      q["dof"] = c.dof;
      q["p_value"] = Num(c.p_value, at + "p_value");
      q["disagree"] = c.disagree;
    }
    j[std::string(ToString(c.kind))] = std::move(q);
  }
  return j;
}

// ----- reading -----

SplitHalfSummary ReadSplitHalf(const JsonReader& r, const JsonReader::json& f) {
  const std::string path = "fit.split_half";
  const JsonReader::json& j = r.Object(f, "fit", "split_half");
  SplitHalfSummary summary;
  summary.significance = r.Number(j, path, "significance");
  summary.widening = r.Number(j, path, "widening");
  if (!(summary.widening >= 1.0)) {
    r.Fail(fmt::format("'{}.widening' = {} is below 1", path, summary.widening));
  }
  for (SplitKind kind : {SplitKind::kByTime, SplitKind::kInterleaved}) {
    const std::string key(ToString(kind));
    if (!j.contains(key)) continue;
    const JsonReader::json& q = r.Object(j, path, key);
    const std::string at = JsonReader::Join(path, key);
    SplitHalfComparison c;
    c.kind = kind;
    const JsonReader::json& counts =
        r.ArrayValue(r.Field(q, at, "positions"), at + ".positions", 2);
    c.positions_first = static_cast<int>(r.NumberValue(counts[0], at + ".positions[0]"));
    c.positions_second = static_cast<int>(r.NumberValue(counts[1], at + ".positions[1]"));
    c.determined = r.Bool(q, at, "determined");
    if (c.determined) {
      c.dof = static_cast<int>(r.Integer(q, at, "dof", 1, kNumModelParameters));
      const JsonReader::json& z =
          r.ArrayValue(r.Field(q, at, "z"), at + ".z", static_cast<std::size_t>(c.dof));
      for (std::size_t i = 0; i < z.size(); ++i) {
        c.z.push_back(r.NumberValue(z[i], fmt::format("{}.z[{}]", at, i)));
      }
      c.rms_z = r.Number(q, at, "rms_z");
      c.chi2 = r.Number(q, at, "chi2");
      c.p_value = r.Number(q, at, "p_value");
      c.disagree = r.Bool(q, at, "disagree");
    }
    summary.comparisons.push_back(std::move(c));
  }
  return summary;
}

// The parameters (or, with `is_std`, their 1σ) of `object`, checked for what
// a calibration can hold.
ErrorModel ReadModel(const JsonReader& r,
                     const json& object,
                     const std::string& path,
                     bool is_std) {
  ErrorModel m;
  m.bias_mps2 = r.Vector(object, path, "bias_mps2");
  m.scale_factor_error = r.Vector(object, path, "scale_factor_error");
  const json& angles = r.Object(object, path, "non_orthogonality_rad");
  const std::string apath = JsonReader::Join(path, "non_orthogonality_rad");
  m.theta_yz_rad = r.Number(angles, apath, "yz");
  m.theta_zx_rad = r.Number(angles, apath, "zx");
  m.theta_zy_rad = r.Number(angles, apath, "zy");
  // A bias of 1e308 would be applied as it is: beyond a few g it is a
  // corrupt file, not a sensor (plausible.h). Its 1σ too.
  for (int i = 0; i < 3; ++i) {
    if (!(std::abs(m.bias_mps2[i]) <= kMaxBiasMps2)) {
      r.Fail(
          fmt::format("'{}bias_mps2[{}]' = {} is beyond any accelerometer's bias (±{:g} "
                      "m/s², 10 g)",
                      path.empty() ? "" : path + ".",
                      i,
                      m.bias_mps2[i],
                      kMaxBiasMps2));
    }
  }
  if (is_std) {
    const auto v = ToVector(m);
    for (int i = 0; i < kNumModelParameters; ++i) {
      if (v[i] < 0.0) {
        r.Fail(fmt::format("'{}' has a negative standard deviation ({} = {})",
                           path,
                           kParameterNames[i],
                           v[i]));
      }
    }
  } else {
    for (int i = 0; i < 3; ++i) {
      if (!(std::abs(m.scale_factor_error[i]) < kMaxScaleFactorError)) {
        r.Fail(fmt::format(
            "'{}scale_factor_error[{}]' = {} is outside (-0.5, 0.5): the axis "
            "would read {:.3g} times the true value",
            path.empty() ? "" : path + ".",
            i,
            m.scale_factor_error[i],
            1.0 + m.scale_factor_error[i]));
      }
    }
    for (auto [name, v] : {std::pair{"yz", m.theta_yz_rad},
                           std::pair{"zx", m.theta_zx_rad},
                           std::pair{"zy", m.theta_zy_rad}}) {
      if (!(std::abs(v) < kMaxNonOrthogonalityRad)) {
        r.Fail(
            fmt::format("'non_orthogonality_rad.{}' = {} rad is not a small angle "
                        "(|angle| must be below pi/4)",
                        name,
                        v));
      }
    }
  }
  return m;
}

json InputJson(const Calibration& c) {
  json input = {{"units", std::string(ToString(c.input_units))},
                {"mps2_per_unit", Num(c.mps2_per_unit, "input.mps2_per_unit")}};
  if (!c.scale_reference.empty()) input["scale_reference"] = c.scale_reference;
  if (c.input_layout) {
    input["columns"] = c.input_layout->columns;
    input["time_unit"] = c.input_layout->time_unit;
    if (c.input_layout->rate_hz > 0.0) {
      input["rate_hz"] = Num(c.input_layout->rate_hz, "input.rate_hz");
    }
  }
  return input;
}

json FitJson(const FitSummary& f) {
  json fit = {{"positions", f.positions},
              {"residual_rms_before_mps2",
               Num(f.residual_rms_before_mps2, "fit.residual_rms_before_mps2")},
              {"residual_rms_after_mps2",
               Num(f.residual_rms_after_mps2, "fit.residual_rms_after_mps2")},
              {"iterations", f.iterations},
              {"converged", f.converged},
              {"excluded_positions", f.excluded_positions}};
  if (f.variance_factor)
    fit["variance_factor"] = Num(*f.variance_factor, "fit.variance_factor");
  if (f.position_scatter_mps2) {
    fit["position_scatter_mps2"] =
        Num(*f.position_scatter_mps2, "fit.position_scatter_mps2");
  }
  if (f.cross_validation_rms_mps2) {
    fit["cross_validation_rms_mps2"] =
        Num(*f.cross_validation_rms_mps2, "fit.cross_validation_rms_mps2");
  }
  if (f.split_half) fit["split_half"] = SplitHalfJson(*f.split_half);
  return fit;
}

json PositionsJson(const std::vector<PositionSummary>& list) {
  json positions = json::array();
  for (std::size_t i = 0; i < list.size(); ++i) {
    const PositionSummary& p = list[i];
    const std::string at = fmt::format("positions[{}].", i);
    json q = {
        {"start_s", Num(p.start_s, at + "start_s")},
        {"end_s", Num(p.end_s, at + "end_s")},
        {"samples", p.samples},
        {"mean_mps2", Vec3(p.mean_mps2, at + "mean_mps2")},
        {"sample_std_mps2", Vec3(p.sample_std_mps2, at + "sample_std_mps2")},
        {"residual_before_mps2",
         Num(p.residual_before_mps2, at + "residual_before_mps2")},
        {"residual_after_mps2", Num(p.residual_after_mps2, at + "residual_after_mps2")},
        {"used", p.used}};
    if (p.cross_validation_residual_mps2) {
      q["cross_validation_residual_mps2"] =
          Num(*p.cross_validation_residual_mps2, at + "cross_validation_residual_mps2");
    }
    positions.push_back(std::move(q));
  }
  return positions;
}

void ReadInput(const JsonReader& r, const json& input, Calibration& c) {
  const std::string units = r.String(input, "input", "units");
  const auto parsed_units = ParseAccelUnits(units);
  if (!parsed_units) {
    r.Fail(fmt::format("unknown units '{}' in 'input.units' (known: mps2, g, counts)",
                       units));
  }
  c.input_units = *parsed_units;
  c.mps2_per_unit = r.Number(input, "input", "mps2_per_unit");
  if (!(c.mps2_per_unit >= kStandardGravityMps2 / kMaxCountsPerG &&
        c.mps2_per_unit <= kStandardGravityMps2 / kMinCountsPerG)) {
    r.Fail(fmt::format(
        "'input.mps2_per_unit' = {} is not a sensor's scale (between {:g} and "
        "{:g} counts per g)",
        c.mps2_per_unit,
        kMinCountsPerG,
        kMaxCountsPerG));
  }
  if (const auto fixed = FixedMps2PerUnit(c.input_units);
      fixed && std::abs(c.mps2_per_unit - *fixed) > 1e-9 * *fixed) {
    r.Fail(fmt::format("'input.mps2_per_unit' is {} but units '{}' mean {} m/s² per unit",
                       c.mps2_per_unit,
                       units,
                       *fixed));
  }
  if (input.contains("scale_reference")) {
    c.scale_reference = r.String(input, "input", "scale_reference");
    if (c.scale_reference != "fitted_sphere" && c.scale_reference != "datasheet") {
      r.Fail(fmt::format(
          "'input.scale_reference' is '{}'; expected fitted_sphere or datasheet",
          c.scale_reference));
    }
  }
  if (input.contains("columns")) {
    Calibration::InputLayout layout;
    layout.columns = r.String(input, "input", "columns");
    if (input.contains("time_unit")) {
      layout.time_unit = r.String(input, "input", "time_unit");
      if (!ParseTimeUnit(layout.time_unit)) {
        r.Fail(fmt::format("unknown 'input.time_unit' '{}'", layout.time_unit));
      }
    }
    if (const auto rate = r.OptionalNumber(input, "input", "rate_hz")) {
      if (!(*rate > 0.0 && *rate <= 1e6)) {
        r.Fail(fmt::format("'input.rate_hz' = {} is not a sample rate (0-1 MHz)", *rate));
      }
      layout.rate_hz = *rate;
    }
    c.input_layout = layout;
  }
}

BiasDrift ReadBiasDrift(const JsonReader& r, const json& j) {
  BiasDrift drift;
  drift.mps2_per_s = r.Vector(j, "", "bias_drift_mps2_per_s");
  drift.reference_time_s = r.Number(j, "", "bias_reference_time_s");
  drift.p_value = r.Number(j, "", "bias_drift_p_value");
  if (j.contains("std") && j["std"].contains("bias_drift_mps2_per_s")) {
    drift.std_mps2_per_s = r.Vector(j["std"], "std", "bias_drift_mps2_per_s");
  }
  return drift;
}

FitSummary ReadFit(const JsonReader& r, const json& f) {
  FitSummary fit;
  fit.positions = static_cast<int>(r.Integer(f, "fit", "positions", 0));
  fit.residual_rms_before_mps2 = r.Number(f, "fit", "residual_rms_before_mps2");
  fit.residual_rms_after_mps2 = r.Number(f, "fit", "residual_rms_after_mps2");
  fit.iterations = static_cast<int>(r.Integer(f, "fit", "iterations", 0));
  fit.converged = r.Bool(f, "fit", "converged");
  if (f.contains("excluded_positions")) {
    fit.excluded_positions =
        static_cast<int>(r.Integer(f, "fit", "excluded_positions", 0));
  }
  fit.variance_factor = r.OptionalNumber(f, "fit", "variance_factor");
  fit.position_scatter_mps2 = r.OptionalNumber(f, "fit", "position_scatter_mps2");
  fit.cross_validation_rms_mps2 = r.OptionalNumber(f, "fit", "cross_validation_rms_mps2");
  if (f.contains("split_half")) fit.split_half = ReadSplitHalf(r, f);
  return fit;
}

std::vector<PositionSummary> ReadPositions(const JsonReader& r, const json& ps) {
  std::vector<PositionSummary> positions;
  if (!ps.is_array()) {
    r.Fail(fmt::format("field 'positions' must be an array, found {}",
                       JsonReader::TypeName(ps)));
  }
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const std::string at = fmt::format("positions[{}]", i);
    if (!ps[i].is_object()) {
      r.Fail(fmt::format(
          "'{}' must be an object, found {}", at, JsonReader::TypeName(ps[i])));
    }
    const json& q = ps[i];
    PositionSummary p;
    p.start_s = r.Number(q, at, "start_s");
    p.end_s = r.Number(q, at, "end_s");
    for (const double t : {p.start_s, p.end_s}) {
      if (!(std::abs(t) <= kMaxTimeS)) {
        r.Fail(
            fmt::format("'{}' has a time of {:.6g} s, beyond any logger's clock", at, t));
      }
    }
    p.samples = static_cast<std::size_t>(
        r.Integer(q, at, "samples", 0, std::numeric_limits<long long>::max()));
    p.mean_mps2 = r.Vector(q, at, "mean_mps2");
    p.sample_std_mps2 = r.Vector(q, at, "sample_std_mps2");
    p.residual_before_mps2 = r.Number(q, at, "residual_before_mps2");
    p.residual_after_mps2 = r.Number(q, at, "residual_after_mps2");
    p.cross_validation_residual_mps2 =
        r.OptionalNumber(q, at, "cross_validation_residual_mps2");
    p.used = q.contains("used") ? r.Bool(q, at, "used") : true;
    positions.push_back(p);
  }
  return positions;
}

std::vector<std::string> ReadWarnings(const JsonReader& r, const json& w) {
  std::vector<std::string> warnings;
  if (!w.is_array()) {
    r.Fail(fmt::format("field 'warnings' must be an array of strings, found {}",
                       JsonReader::TypeName(w)));
  }
  for (std::size_t i = 0; i < w.size(); ++i) {
    if (!w[i].is_string()) {
      r.Fail(fmt::format(
          "'warnings[{}]' must be a string, found {}", i, JsonReader::TypeName(w[i])));
    }
    warnings.push_back(w[i].get<std::string>());
  }
  return warnings;
}

}  // namespace

std::string CalibrationToJson(const Calibration& c) {
  json j;
  // An IMU file when the gyroscope is calibrated too; accelerometer-only
  // calibrations keep the format every reader already knows.
  j["format"] = c.gyroscope ? kImuCalibrationFormat : kCalibrationFormat;
  j["model"] = std::string(ToString(c.model_kind));
  j["gravity_mps2"] = Num(c.gravity_mps2, "gravity_mps2");
  j["input"] = InputJson(c);
  PutModel(j, c.model, "");
  if (c.bias_drift) {
    j["bias_drift_mps2_per_s"] = Vec3(c.bias_drift->mps2_per_s, "bias_drift_mps2_per_s");
    j["bias_reference_time_s"] =
        Num(c.bias_drift->reference_time_s, "bias_reference_time_s");
    j["bias_drift_p_value"] = Num(c.bias_drift->p_value, "bias_drift_p_value");
  }
  if (c.std) {
    json s;
    PutModel(s, *c.std, "std.");
    if (c.bias_drift) {
      s["bias_drift_mps2_per_s"] =
          Vec3(c.bias_drift->std_mps2_per_s, "std.bias_drift_mps2_per_s");
    }
    j["std"] = s;
  }
  if (c.fit) j["fit"] = FitJson(*c.fit);
  j["positions"] = PositionsJson(c.positions);
  j["warnings"] = c.warnings;
  if (c.gyroscope) j["gyroscope"] = internal::GyroToJson(*c.gyroscope);
  if (c.imported_from) {
    if (c.std) {
      throw Error(ErrorKind::kInput,
                  "an imported calibration has no 1σ, but this one has 'std'");
    }
    j["imported_from"] = *c.imported_from;
  }
  if (c.provenance) {
    j["provenance"] = {{"mpcal_version", c.provenance->mpcal_version},
                       {"input", c.provenance->input},
                       {"options", c.provenance->options}};
  }
  // Invalid UTF-8 in a path or message is replaced rather than thrown about.
  return j.dump(2, ' ', false, json::error_handler_t::replace) + "\n";
}

Calibration CalibrationFromJson(const std::string& text, const std::string& origin) {
  const JsonReader r(fmt::format("calibration file '{}'", origin), Stage::kCalibrate);
  const json j = r.Parse(text);
  // mpcal.imu/1 is mpcal.accelerometer/1 plus a `gyroscope` block.
  const bool imu = j.is_object() && j.contains("format") && j["format"].is_string() &&
                   j["format"].get<std::string>().starts_with(
                       std::string(internal::kImuFormatFamily) + "/");
  r.ExpectFormat(j, imu ? internal::kImuFormatFamily : kFormatFamily, kMajorVersion);

  Calibration c;
  const std::string model = r.String(j, "", "model");
  const auto kind = ParseModelKind(model);
  if (!kind) {
    r.Fail(fmt::format("unknown model '{}' (known: {}, {})",
                       model,
                       ToString(ModelKind::kShinElSheimy9),
                       ToString(ModelKind::kBiasScale6)));
  }
  c.model_kind = *kind;
  c.gravity_mps2 = r.Number(j, "", "gravity_mps2");
  if (!IsPlausibleGravity(c.gravity_mps2)) {
    r.Fail(
        fmt::format("'gravity_mps2' = {} is not a magnitude of gravity on Earth (m/s²)",
                    c.gravity_mps2));
  }
  ReadInput(r, r.Object(j, "", "input"), c);
  c.model = ReadModel(r, j, "", false);
  if (c.model_kind == ModelKind::kBiasScale6 &&
      (c.model.theta_yz_rad != 0.0 || c.model.theta_zx_rad != 0.0 ||
       c.model.theta_zy_rad != 0.0)) {
    r.Fail(
        "model 'bias-scale-6' has no non-orthogonality, but 'non_orthogonality_rad' is "
        "not "
        "zero");
  }
  if (j.contains("std")) {
    r.Object(j, "", "std");
    c.std = ReadModel(r, j["std"], "std", true);
  }
  if (j.contains("bias_drift_mps2_per_s")) c.bias_drift = ReadBiasDrift(r, j);
  if (j.contains("fit")) c.fit = ReadFit(r, r.Object(j, "", "fit"));
  if (j.contains("positions")) c.positions = ReadPositions(r, j["positions"]);
  if (j.contains("warnings")) c.warnings = ReadWarnings(r, j["warnings"]);
  if (j.contains("provenance")) {
    const json& p = r.Object(j, "", "provenance");
    Provenance prov;
    prov.mpcal_version = r.String(p, "provenance", "mpcal_version");
    prov.input = r.String(p, "provenance", "input");
    prov.options = r.String(p, "provenance", "options");
    c.provenance = prov;
  }
  if (imu) c.gyroscope = internal::GyroFromJson(r, r.Field(j, "", "gyroscope"));
  if (j.contains("imported_from")) {
    c.imported_from = r.String(j, "", "imported_from");
    if (c.std ||
        (c.gyroscope && (c.gyroscope->bias_std_radps || c.gyroscope->m_covariance))) {
      r.Fail(
          "'imported_from' says the calibration was read from another tool's file, "
          "which gives no 1σ, but the file has a 1σ ('std')");
    }
  }
  return c;
}

std::string JsonFormatTag(const std::string& text) {
  const json j = json::parse(text, nullptr, false);
  if (!j.is_object() || !j.contains("format") || !j["format"].is_string()) return "";
  return j["format"].get<std::string>();
}

Calibration ReadCalibrationFile(const std::string& path) {
  std::error_code ec;
  if (path != "-" && std::filesystem::is_directory(path, ec)) {
    throw Error(
        ErrorKind::kIo,
        fmt::format("calibration file '{}' is a directory; give the JSON file", path));
  }
  // Checked before it is read to the end: /dev/zero or a video named by
  // mistake is refused at once.
  const std::string text =
      ReadTextInput(path, kMaxCalibrationFileBytes, "calibration file");
  return CalibrationFromJson(text, path == "-" ? "<stdin>" : path);
}

void WriteCalibrationFile(const std::string& path, const Calibration& calibration) {
  WriteFileAtomically(path, CalibrationToJson(calibration));
}

}  // namespace mpcal
