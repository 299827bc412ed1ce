/// \file calibration_file.h
/// \brief The calibration file: JSON, `"format": "mpcal.accelerometer/1"`,
/// SI units, every name carrying its unit. The schema is in the README.
#pragma once

#include <string>

#include "mpcal/calibration.h"

namespace mpcal {

/// The format tag this version writes.
inline constexpr const char* kCalibrationFormat = "mpcal.accelerometer/1";
/// The format tag of an IMU file: the accelerometer's fields as above plus a
/// `gyroscope` block (Calibration::gyroscope set). Readers take both.
inline constexpr const char* kImuCalibrationFormat = "mpcal.imu/1";

/// Serialises to the JSON text of the file (pretty-printed, newline-ended).
std::string CalibrationToJson(const Calibration& calibration);

/// Parses the JSON text of a calibration file. `origin` names the source in
/// messages (a path).
/// \throws mpcal::Error for malformed JSON, a missing or wrongly-typed field,
///   an unknown format or major version, an unknown model or unit, or a
///   non-finite value.
Calibration CalibrationFromJson(const std::string& text, const std::string& origin);

/// The `"format"` tag of an mpcal JSON file's text ("mpcal.imu/1",
/// "mpcal.noise/1", ...), so that a command taking either kind of file can
/// tell them apart; empty when the text is not a JSON object with a string
/// "format".
std::string JsonFormatTag(const std::string& text);

/// Reads and parses a calibration file.
/// \throws mpcal::Error as CalibrationFromJson, or when unreadable.
Calibration ReadCalibrationFile(const std::string& path);

/// Writes atomically (temporary file beside it, then rename).
/// \throws mpcal::Error when the file cannot be written.
void WriteCalibrationFile(const std::string& path, const Calibration& calibration);

}  // namespace mpcal
