// Reading and writing the tools' YAML (yaml-cpp stays inside this room).
#include "export/tool_yaml.h"

#include <cctype>
#include <cmath>

#include <fmt/format.h>

#include "mpcal/error.h"
#include "mpcal/noise_file.h"

namespace mpcal::export_formats {

YAML::Node LoadToolYaml(const ImportFile& file) {
  std::string text = file.text;
  // OpenCV's FileStorage writes and wants "%YAML:1.0", which is not a YAML
  // 1.x directive; the line says nothing more.
  if (text.starts_with("%YAML:")) {
    const auto eol = text.find('\n');
    text = eol == std::string::npos ? std::string() : text.substr(eol + 1);
  }
  try {
    return YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw Error(
        ErrorKind::kInput,
        fmt::format("'{}' line {}: not YAML ({})", file.path, e.mark.line + 1, e.msg));
  }
}

YAML::Node ImuBlock(const YAML::Node& root, const ImportFile& file) {
  if (!root.IsMap()) {
    throw Error(
        ErrorKind::kInput,
        fmt::format("'{}' is not a map of keys; an IMU file of Kalibr or OpenVINS "
                    "starts with 'imu0:'",
                    file.path));
  }
  if (root["imu0"] && root["imu0"].IsMap()) return root["imu0"];
  if (root["cam0"]) {
    throw Error(
        ErrorKind::kInput,
        fmt::format("'{}' is a camera chain (it has 'cam0:'), not an IMU file; give "
                    "the IMU's yaml (with 'imu0:')",
                    file.path));
  }
  throw Error(
      ErrorKind::kInput,
      fmt::format("'{}' has no 'imu0:' map; an IMU file of Kalibr or OpenVINS names "
                  "its IMU so",
                  file.path));
}

Eigen::Matrix3d YamlMatrix3(const YAML::Node& map,
                            const std::string& key,
                            const std::string& where,
                            const ImportFile& file) {
  const YAML::Node n = map[key];
  if (!n) {
    throw Error(ErrorKind::kInput,
                fmt::format("'{}': '{}.{}' is missing", file.path, where, key));
  }
  auto bad = [&] {
    return Error(ErrorKind::kInput,
                 fmt::format("'{}' line {}: '{}.{}' is not a 3×3 matrix (three lists of "
                             "three numbers)",
                             file.path,
                             n.Mark().line + 1,
                             where,
                             key));
  };
  if (!n.IsSequence() || n.size() != 3) throw bad();
  Eigen::Matrix3d m;
  for (std::size_t i = 0; i < 3; ++i) {
    if (!n[i].IsSequence() || n[i].size() != 3) throw bad();
    for (std::size_t j = 0; j < 3; ++j) {
      double v = 0.0;
      if (!n[i][j].IsScalar() || !YAML::convert<double>::decode(n[i][j], v) ||
          !std::isfinite(v)) {
        throw bad();
      }
      m(static_cast<int>(i), static_cast<int>(j)) = v;
    }
  }
  return m;
}

std::string YamlString(const YAML::Node& map,
                       const std::string& key,
                       const std::string& where,
                       const ImportFile& file) {
  const YAML::Node n = map[key];
  if (!n || !n.IsScalar()) {
    throw Error(ErrorKind::kInput,
                fmt::format("'{}': '{}.{}' is missing", file.path, where, key));
  }
  return n.Scalar();
}

std::string YamlMatrixLines(const std::string& key,
                            const Eigen::MatrixXd& m,
                            int indent) {
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  std::string out = pad + key + ":\n";
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    out += pad + "  - [";
    for (Eigen::Index j = 0; j < m.cols(); ++j) {
      // The shortest text that reads back as the same double.
      out += fmt::format("{}{}", j == 0 ? "" : ", ", m(i, j) + 0.0);
    }
    out += "]\n";
  }
  return out;
}

namespace {

// A value that is not a measurement says so on its own line, before its key.
std::string NoiseLine(const std::string& pad,
                      const KalibrFile& k,
                      const char* key,
                      const KalibrValue& v,
                      const char* unit,
                      std::vector<ExportNote>* notes) {
  std::string out;
  if (v.upper_bound) {
    notes->push_back(ExportNote{
        ExportNoteKind::kUpperBound, key, k.Written(v), unit, v.record_needed_s});
    out += fmt::format(
        "{}# {} NOT MEASURED: the upper bound from a record too short to show it{}\n",
        pad,
        key,
        v.record_needed_s ? fmt::format(" (record at least {} to measure it)",
                                        FormatRecordLength(*v.record_needed_s))
                          : "");
  }
  out += fmt::format("{}{}: {}  # {} ({} axis){}\n",
                     pad,
                     key,
                     k.Written(v),
                     unit,
                     static_cast<char>('x' + v.axis),
                     k.inflate == 1.0
                         ? std::string(v.upper_bound ? "; upper bound" : "")
                         : fmt::format("; INFLATED x{:g}: the record's {} {}",
                                       k.inflate,
                                       v.upper_bound ? "upper bound" : "measured value",
                                       v.value));
  return out;
}

}  // namespace

std::string NoiseKeyLines(const ExportSources& s,
                          const ExportOptions& o,
                          int indent,
                          std::vector<ExportNote>* notes) {
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  // A ROS name: letters, digits, '_', '/', '~' (written unquoted).
  for (const char c : o.rostopic) {
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '/' ||
          c == '~')) {
      throw Error(ErrorKind::kOption,
                  fmt::format("'{}' is not a ROS topic name (letters, digits, '_', '/')",
                              o.rostopic));
    }
  }
  const KalibrFile k = KalibrYaml(s.noise->result, s.noise->input, o.rostopic, o.inflate);
  std::string out;
  if (k.inflate != 1.0) {
    out += fmt::format(
        "{}# INFLATED x{:g} at the user's request: the four noise values below are "
        "{:g} times the record's, which each line's comment gives.\n",
        pad,
        k.inflate,
        k.inflate);
  }
  out += NoiseLine(pad,
                   k,
                   "accelerometer_noise_density",
                   k.accel_noise_density,
                   "m/s^2/sqrt(Hz)",
                   notes);
  out += NoiseLine(
      pad, k, "accelerometer_random_walk", k.accel_random_walk, "m/s^3/sqrt(Hz)", notes);
  out += NoiseLine(
      pad, k, "gyroscope_noise_density", k.gyro_noise_density, "rad/s/sqrt(Hz)", notes);
  out += NoiseLine(
      pad, k, "gyroscope_random_walk", k.gyro_random_walk, "rad/s^2/sqrt(Hz)", notes);
  out += fmt::format("{}rostopic: {}\n", pad, o.rostopic);
  out += fmt::format("{}time_offset: 0.0\n", pad);
  out += fmt::format("{}update_rate: {}  # Hz{}\n",
                     pad,
                     o.rate_hz.value_or(s.noise->result.rate_hz),
                     o.rate_hz ? "" : " (the noise record's)");
  return out;
}

}  // namespace mpcal::export_formats
