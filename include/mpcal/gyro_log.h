/// \file gyro_log.h
/// \brief A gyroscope recorded in a file of its own, row by row with the
/// accelerometer's (imu_tk's xsens_acc.mat and xsens_gyro.mat): its three
/// columns become the recording's gyroscope readings.
#pragma once

#include <string>

#include "mpcal/log_reader.h"
#include "mpcal/recording.h"
#include "mpcal/units.h"

namespace mpcal {

/// Reads a gyroscope's own log: a time column and three reading columns,
/// into the `accel` of the Recording returned (for MergeGyroLog). The columns
/// are those `options.columns` maps with the keys t, gx, gy, gz, else those
/// the header names (t/time..., and gx/gyr_x/gyro_x, wx, omega_x, rate_x or
/// a bare x, and y, z), else t, x, y, z in order. `options` is read as for
/// the main log (time unit, rate, gyroscope units: raw counts are allowed
/// the ADC's range); its accelerometer units are not used.
/// \throws mpcal::Error as ReadLog, and (kColumns, kOption, with
///   Option::kGyroLogColumns in the advice) when the columns are not found.
Recording ReadGyroLog(const std::string& path, LogOptions options);

/// Takes the three reading columns of `gyro_log` (read as an accelerometer
/// log: t, x, y, z) as the gyroscope of `recording`, in `units` (deg/s are
/// converted to rad/s; counts are kept). The rows must be the same samples:
/// as many, at the same times (within a hundredth of the sample period).
/// \throws mpcal::Error naming both sources when the row counts or a time
///   differ, or `recording` already has gyroscope readings.
void MergeGyroLog(Recording& recording, const Recording& gyro_log, GyroUnits units);

}  // namespace mpcal
