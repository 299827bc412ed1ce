// A calibration as PX4's and ArduPilot's parameters, and back
// (filter_formats.h). Both autopilots correct an accelerometer reading of
// their driver (m/s²) per axis as (reading − offset) × scale, and a
// gyroscope reading (rad/s) as reading − offset: PX4
// src/lib/sensor_calibration/Accelerometer.hpp and Gyroscope.hpp
// (Correct), ArduPilot libraries/AP_InertialSensor/
// AP_InertialSensor_Backend.cpp (_rotate_and_correct_accel, _gyro).
// mpcal's a = T·diag(1/(1 + s))·(y − b) is that with T = I: offset = b,
// scale = 1/(1 + s); T and the gyroscope's M are what they drop.
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include <fast_float/fast_float.h>
#include <fmt/format.h>
#include <Eigen/Dense>

#include "export/filter_formats.h"
#include "mpcal/error.h"

namespace mpcal {

namespace {

enum class Autopilot { kPx4, kArduPilot };

constexpr const char* kAutopilotAxes[] = {"X", "Y", "Z"};

// Unit vectors spread over the sphere (a Fibonacci lattice): the worst
// direction of a 3×3 map is found to well below a per cent of its value
// with a few thousand.
template <typename F>
double WorstOverDirections(const F& f) {
  constexpr int kDirections = 4000;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  double worst = 0.0;
  for (int i = 0; i < kDirections; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / kDirections;
    const double r = std::sqrt(1.0 - z * z);
    const Eigen::Vector3d u(r * std::cos(golden * i), r * std::sin(golden * i), z);
    worst = std::max(worst, f(u));
  }
  return worst;
}

struct ParameterNames {
  std::string acc_off[3], acc_scale[3], gyro_off[3];
};

ParameterNames NamesOf(Autopilot autopilot) {
  ParameterNames n;
  for (int i = 0; i < 3; ++i) {
    if (autopilot == Autopilot::kPx4) {
      n.acc_off[i] = fmt::format("CAL_ACC0_{}OFF", kAutopilotAxes[i]);
      n.acc_scale[i] = fmt::format("CAL_ACC0_{}SCALE", kAutopilotAxes[i]);
      n.gyro_off[i] = fmt::format("CAL_GYRO0_{}OFF", kAutopilotAxes[i]);
    } else {
      n.acc_off[i] = fmt::format("INS_ACCOFFS_{}", kAutopilotAxes[i]);
      n.acc_scale[i] = fmt::format("INS_ACCSCAL_{}", kAutopilotAxes[i]);
      n.gyro_off[i] = fmt::format("INS_GYROFFS_{}", kAutopilotAxes[i]);
    }
  }
  return n;
}

// ArduPilot reads a parameter file in pieces of at most 98 characters
// (fgets into a char[100] with sizeof - 1, AP_Param::read_param_defaults_file):
// the rest of a longer comment line would be read as a parameter line. Every
// line stays within 98 characters before its newline (a newline read alone
// is refused by AP_Param::parse_param_line).
std::string AutopilotComment(std::string text) {
  constexpr std::size_t kMaxText = 96;
  for (char& ch : text) {
    if (ch == '\n' || ch == '\r') ch = ' ';
  }
  if (text.size() > kMaxText) text = text.substr(0, kMaxText - 3) + "...";
  return "# " + text + "\n";
}

std::string ParameterLine(Autopilot autopilot, const std::string& name, double value) {
  // Nine significant digits round-trip a float (both autopilots store one).
  if (autopilot == Autopilot::kPx4)
    return fmt::format("1\t1\t{}\t{:.9g}\t9\n", name, value);
  return fmt::format("{},{:.9g}\n", name, value);
}

}  // namespace

AutopilotLoss AutopilotModelLoss(const Calibration& c) {
  AutopilotLoss loss;
  // mpcal: a = T·D·(y − b); the autopilot: D·(y − b) = T⁻¹·a.
  const Eigen::Matrix3d t_inv = c.model.NonOrthogonality().inverse();
  const double g = c.gravity_mps2;
  loss.accel_max_error_mps2 = WorstOverDirections(
      [&](const Eigen::Vector3d& u) { return ((u - t_inv * u) * g).norm(); });
  loss.accel_max_tilt_rad = WorstOverDirections([&](const Eigen::Vector3d& u) {
    const Eigen::Vector3d w = t_inv * u;
    return std::atan2(u.cross(w).norm(), u.dot(w));
  });
  if (c.gyroscope) {
    // mpcal: ω = M·(r − b); the autopilot: r − b = M⁻¹·ω.
    const Eigen::Matrix3d m_inv = c.gyroscope->m.inverse();
    loss.gyro_max_relative_error = WorstOverDirections(
        [&](const Eigen::Vector3d& u) { return (u - m_inv * u).norm(); });
    if (c.gyroscope->g_sensitivity_radps_per_mps2) {
      const Eigen::Matrix3d& gs = *c.gyroscope->g_sensitivity_radps_per_mps2;
      loss.gyro_g_sensitivity_radps = WorstOverDirections(
          [&](const Eigen::Vector3d& u) { return (c.gyroscope->m * gs * u * g).norm(); });
    }
  }
  return loss;
}

namespace {

// The comment lines that open the file: the model, what it drops for this
// sensor, and how the ground station loads it.
std::string AutopilotHeader(const Calibration& c,
                            Autopilot autopilot,
                            const std::string& input) {
  const bool px4 = autopilot == Autopilot::kPx4;
  const AutopilotLoss loss = AutopilotModelLoss(c);
  std::string t;
  const auto comment = [&](const std::string& line) { t += AutopilotComment(line); };
  if (px4) comment("Onboard parameters for Vehicle 1");
  comment(fmt::format(
      "{} calibration by mpcal {}", px4 ? "PX4" : "ArduPilot", MPCAL_VERSION));
  comment(fmt::format("from '{}'", input));
  comment("Correction per axis: (reading - OFF) * SCALE, reading in m/s^2 (gyro rad/s,");
  comment(
      px4 ? "offset only), then CAL_ACC0_ROT: the readings of sensor_accel, uncorrected."
          : "offset only), after its sensor-orientation rotation: the IMU's readings, "
            "uncorrected.");
  comment("Offsets and scales only: this model drops the non-orthogonality, for this");
  comment(fmt::format(
      "sensor up to {:.3g} m/s^2 ({:.3g} mg) and {:.3g} deg of tilt at {:.6g} m/s^2.",
      loss.accel_max_error_mps2,
      loss.accel_max_error_mps2 / kStandardGravityMps2 * 1e3,
      loss.accel_max_tilt_rad * 180.0 / std::numbers::pi,
      c.gravity_mps2));
  if (loss.gyro_max_relative_error) {
    comment(fmt::format(
        "Gyroscope: offsets only; its scale and misalignment dropped: up to {:.3g} %",
        *loss.gyro_max_relative_error * 100.0));
    comment(fmt::format("of the rate ({:.3g} deg/s at 360 deg/s).",
                        *loss.gyro_max_relative_error * 360.0));
  }
  if (loss.gyro_g_sensitivity_radps) {
    comment(fmt::format("g-sensitivity dropped: up to {:.3g} deg/s at 1 g.",
                        *loss.gyro_g_sensitivity_radps * 180.0 / std::numbers::pi));
  }
  if (px4) {
    comment("Loads onto the sensor whose id is in CAL_ACC0_ID (and CAL_GYRO0_ID) on the");
    comment("vehicle. Vehicle id 1: change the first column if MAV_SYS_ID differs.");
    comment("");
    comment("Vehicle-Id\tComponent-Id\tName\tValue\tType");
  } else {
    comment("INS_GYR_CAL=1 (default) measures the gyroscope offsets at every boot.");
  }
  return t;
}

// What the model drops, as facts: the largest entry of each term.
std::vector<ExportNote> AutopilotNotes(const Calibration& c) {
  std::vector<ExportNote> notes;
  const ErrorModel& m = c.model;
  notes.push_back(ExportNote{
      ExportNoteKind::kTermDropped,
      "non_orthogonality",
      std::max(
          {std::abs(m.theta_yz_rad), std::abs(m.theta_zx_rad), std::abs(m.theta_zy_rad)}),
      "rad",
      std::nullopt});
  if (c.gyroscope) {
    notes.push_back(
        ExportNote{ExportNoteKind::kTermDropped,
                   "gyroscope_m",
                   (c.gyroscope->m - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(),
                   "",
                   std::nullopt});
    if (c.gyroscope->g_sensitivity_radps_per_mps2) {
      notes.push_back(
          ExportNote{ExportNoteKind::kTermDropped,
                     "g_sensitivity",
                     c.gyroscope->g_sensitivity_radps_per_mps2->cwiseAbs().maxCoeff(),
                     "rad/s per m/s^2",
                     std::nullopt});
    }
  }
  return notes;
}

ExportedFile WriteAutopilot(const ExportSources& s, Autopilot autopilot) {
  const Calibration& c = *s.calibration;
  const std::string& input = s.calibration_path;
  if (c.input_units == AccelUnits::kCounts ||
      (c.gyroscope && c.gyroscope->input_units == GyroUnits::kCounts)) {
    throw Error(
        ErrorKind::kUnits,
        fmt::format("'{}' calibrates raw counts; an autopilot applies its parameters to "
                    "its driver's m/s^2 and rad/s: calibrate a log of those readings",
                    input));
  }
  const ParameterNames names = NamesOf(autopilot);
  ExportedFile f;
  std::string& t = f.text;
  t = AutopilotHeader(c, autopilot, input);
  for (int i = 0; i < 3; ++i) {
    t += ParameterLine(autopilot, names.acc_off[i], c.model.bias_mps2[i]);
  }
  for (int i = 0; i < 3; ++i) {
    t += ParameterLine(
        autopilot, names.acc_scale[i], 1.0 / (1.0 + c.model.scale_factor_error[i]));
  }
  if (c.gyroscope) {
    for (int i = 0; i < 3; ++i) {
      t += ParameterLine(autopilot, names.gyro_off[i], c.gyroscope->bias_radps[i]);
    }
  }
  f.notes = AutopilotNotes(c);
  return f;
}

// name → (value, line) of every parameter line.
std::map<std::string, std::pair<double, int>> ParseParameterLines(
    const std::string& text, Autopilot autopilot, const std::string& origin) {
  std::map<std::string, std::pair<double, int>> values;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    std::string name, value;
    if (autopilot == Autopilot::kPx4) {
      // QGroundControl: five tab-separated fields.
      std::vector<std::string> fields;
      std::string field;
      std::istringstream fs(line);
      while (std::getline(fs, field, '\t')) fields.push_back(field);
      if (fields.size() != 5) {
        throw Error(
            ErrorKind::kFormat,
            fmt::format("{}: line {}: not a QGroundControl parameter line (vehicle id, "
                        "component id, name, value, type, separated by tabs)",
                        origin,
                        number));
      }
      name = fields[2];
      value = fields[3];
    } else {
      // ArduPilot (AP_Param::parse_param_line): name and value separated by
      // any of ", =\t".
      const auto sep = line.find_first_of(", =\t");
      const auto start =
          sep == std::string::npos ? sep : line.find_first_not_of(", =\t", sep);
      if (sep == 0 || start == std::string::npos) {
        throw Error(
            ErrorKind::kFormat,
            fmt::format("{}: line {}: not an ArduPilot parameter line (NAME,VALUE)",
                        origin,
                        number));
      }
      name = line.substr(0, sep);
      value = line.substr(start, line.find_first_of(", =\t", start) - start);
    }
    // The whole field a number, in any locale (fast_float, as mpcal's
    // readers of logs).
    double v = std::numeric_limits<double>::quiet_NaN();
    const auto parsed =
        fast_float::from_chars(value.data(), value.data() + value.size(), v);
    if (value.empty() || parsed.ec != std::errc() ||
        parsed.ptr != value.data() + value.size() || !std::isfinite(v)) {
      throw Error(ErrorKind::kInput,
                  fmt::format("{}: line {}: {} has the value '{}', not a finite number",
                              origin,
                              number,
                              name,
                              value));
    }
    values[name] = {v, number};
  }
  return values;
}

ImportedCalibration ReadAutopilot(const std::vector<ImportFile>& files,
                                  const ImportOptions& options,
                                  Autopilot autopilot) {
  const std::string& origin = files.front().path;
  const auto values = ParseParameterLines(files.front().text, autopilot, origin);
  const ParameterNames names = NamesOf(autopilot);
  const auto get = [&](const std::string& name) -> std::optional<std::pair<double, int>> {
    const auto it = values.find(name);
    if (it == values.end()) return std::nullopt;
    return it->second;
  };
  ImportedCalibration imported;
  Calibration& c = imported.calibration;
  c.model_kind = ModelKind::kBiasScale6;
  c.gravity_mps2 = options.gravity_mps2;
  c.input_units = AccelUnits::kMps2;
  c.mps2_per_unit = 1.0;
  for (int i = 0; i < 3; ++i) {
    const auto off = get(names.acc_off[i]);
    const auto scale = get(names.acc_scale[i]);
    if (!off || !scale) {
      throw Error(ErrorKind::kFormat,
                  fmt::format("{}: no {}: not a {} accelerometer calibration",
                              origin,
                              !off ? names.acc_off[i] : names.acc_scale[i],
                              autopilot == Autopilot::kPx4 ? "PX4" : "ArduPilot"));
    }
    if (!(scale->first > 0.0)) {
      throw Error(ErrorKind::kInput,
                  fmt::format("{}: line {}: {} is {}; a scale is positive",
                              origin,
                              scale->second,
                              names.acc_scale[i],
                              scale->first));
    }
    c.model.bias_mps2[i] = off->first;
    c.model.scale_factor_error[i] = 1.0 / scale->first - 1.0;
  }
  int gyro_found = 0;
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();
  for (int i = 0; i < 3; ++i) {
    if (const auto off = get(names.gyro_off[i])) {
      gyro_bias[i] = off->first;
      ++gyro_found;
    }
  }
  if (gyro_found == 3) {
    GyroCalibration g;
    g.input_units = GyroUnits::kRadps;
    g.radps_per_unit = 1.0;
    g.bias_radps = gyro_bias;
    c.gyroscope = g;
  }
  c.imported_from =
      autopilot == Autopilot::kPx4 ? "PX4 parameters" : "ArduPilot parameters";
  c.provenance = Provenance{MPCAL_VERSION, origin, ""};
  return imported;
}

ExportedFile WritePx4(const ExportSources& s, const ExportOptions&) {
  return WriteAutopilot(s, Autopilot::kPx4);
}
ExportedFile WriteArduPilot(const ExportSources& s, const ExportOptions&) {
  return WriteAutopilot(s, Autopilot::kArduPilot);
}
ImportedCalibration ReadPx4(const std::vector<ImportFile>& files,
                            const ImportOptions& o) {
  return ReadAutopilot(files, o, Autopilot::kPx4);
}
ImportedCalibration ReadArduPilot(const std::vector<ImportFile>& files,
                                  const ImportOptions& o) {
  return ReadAutopilot(files, o, Autopilot::kArduPilot);
}

}  // namespace

namespace export_formats {

ExportFormat Px4() {
  ExportFormat f;
  f.name = "px4";
  f.file = "PX4 parameters (QGroundControl .params)";
  f.calibration = ExportNeed::kRequired;
  f.write = WritePx4;
  f.read = ReadPx4;
  f.import_files = "PARAMS.params";
  return f;
}

ExportFormat ArduPilot() {
  ExportFormat f;
  f.name = "ardupilot";
  f.file = "ArduPilot parameters (.param)";
  f.calibration = ExportNeed::kRequired;
  f.write = WriteArduPilot;
  f.read = ReadArduPilot;
  f.import_files = "PARAMS.param";
  return f;
}

}  // namespace export_formats

}  // namespace mpcal
