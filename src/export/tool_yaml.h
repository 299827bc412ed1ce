// What the YAML formats share: reading a tool's YAML with the one-line
// errors mpcal gives (file, key, what is wrong), and writing matrices and
// the noise keys Kalibr defined (OpenVINS reads the same keys).
#pragma once

#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>
#include <Eigen/Core>

#include "mpcal/export.h"

namespace mpcal::export_formats {

/// The document of `file` (OpenCV's "%YAML:1.0" first line allowed, as
/// OpenVINS writes it). \throws mpcal::Error for YAML that does not parse.
YAML::Node LoadToolYaml(const ImportFile& file);

/// The IMU's block: the map under `imu0` (Kalibr's and OpenVINS's files
/// name the IMU so). \throws mpcal::Error naming what the file is instead
/// (a camera chain, another map, not a map).
YAML::Node ImuBlock(const YAML::Node& root, const ImportFile& file);

/// A 3×3 matrix under `key` of `map` (a list of three lists of three
/// numbers); `where` names the map in messages ("imu0.gyroscopes").
Eigen::Matrix3d YamlMatrix3(const YAML::Node& map,
                            const std::string& key,
                            const std::string& where,
                            const ImportFile& file);
/// A string under `key`.
std::string YamlString(const YAML::Node& map,
                       const std::string& key,
                       const std::string& where,
                       const ImportFile& file);

/// "  key:\n    - [a, b, c]\n ..." at `indent` spaces, every digit kept.
std::string YamlMatrixLines(const std::string& key, const Eigen::MatrixXd& m, int indent);

/// The four noise keys and update_rate, rostopic, time_offset as Kalibr
/// writes them, at `indent` spaces, from the noise file (the largest axis,
/// as mpcal's Kalibr imu.yaml); a value that is a bound says so on its line
/// and adds a note.
std::string NoiseKeyLines(const ExportSources& s,
                          const ExportOptions& o,
                          int indent,
                          std::vector<ExportNote>* notes);

}  // namespace mpcal::export_formats
