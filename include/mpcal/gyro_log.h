/// \file gyro_log.h
/// \brief A gyroscope recorded in a file of its own, row by row with the
/// accelerometer's (imu_tk's xsens_acc.mat and xsens_gyro.mat): its three
/// columns become the recording's gyroscope readings.
#pragma once

#include "mpcal/recording.h"
#include "mpcal/units.h"

namespace mpcal {

/// Takes the three reading columns of `gyro_log` (read as an accelerometer
/// log: t, x, y, z) as the gyroscope of `recording`, in `units` (deg/s are
/// converted to rad/s; counts are kept). The rows must be the same samples:
/// as many, at the same times (within a hundredth of the sample period).
/// \throws mpcal::Error naming both sources when the row counts or a time
///   differ, or `recording` already has gyroscope readings.
void MergeGyroLog(Recording& recording, const Recording& gyro_log, GyroUnits units);

}  // namespace mpcal
