// The `gyroscope` block of an IMU calibration file (mpcal.imu/1), kept apart
// from the accelerometer's fields in calibration_file.cc.
#pragma once

#include <string_view>

#include "io/json_reader.h"
#include "mpcal/gyro_calibration.h"

namespace mpcal::internal {

/// The format family of an IMU file (accelerometer and gyroscope).
inline constexpr std::string_view kImuFormatFamily = "mpcal.imu";

JsonReader::json GyroToJson(const GyroCalibration& gyro);

/// \throws mpcal::Error (through `reader`) for a missing or malformed field.
GyroCalibration GyroFromJson(const JsonReader& reader, const JsonReader::json& object);

}  // namespace mpcal::internal
