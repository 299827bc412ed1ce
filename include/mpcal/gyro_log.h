/// \file gyro_log.h
/// \brief A gyroscope recorded in a stream of its own: row by row with the
/// accelerometer's (imu_tk's xsens_acc.mat and xsens_gyro.mat), or at its own
/// rate and stamps (Sensor Logger's and phyphox's file per sensor, a ROS
/// driver's topic per sensor): its readings become the recording's gyroscope.
#pragma once

#include <string>
#include <vector>

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
/// the ADC's range); its accelerometer units are not used. A recording
/// (bag.h) gives the angular velocity of `options.topic`'s messages.
/// \throws mpcal::Error as ReadLog, and (kColumns, kOption, with
///   Option::kGyroLogColumns in the advice) when the columns are not found.
Recording ReadGyroLog(const std::string& path, LogOptions options);

/// What may make a two-stream calibration wrong, found by MergeGyroLog.
enum class StreamFinding {
  /// The streams cover different spans: their overlap is less than 90 % of
  /// the longer one (one stream much shorter, or clocks that disagree).
  kSpansDiffer,
  /// The gyroscope has a gap within the overlap longer than 5 of its
  /// periods and than one accelerometer period: the rates across it are
  /// interpolated, which invents the rotation of a turn made during it.
  kGyroGap,
};

/// How the gyroscope's readings were put on the accelerometer's rows.
struct StreamMerge {
  /// False: the two logs held the same samples, taken row by row; true:
  /// the gyroscope was resampled onto the accelerometer's stamps.
  bool resampled = false;
  /// Median rate of each stream as read (Hz).
  double accel_rate_hz = 0.0;
  double gyro_rate_hz = 0.0;
  /// Each stream's first and last time, s on the accelerometer's clock.
  double accel_first_s = 0.0, accel_last_s = 0.0;
  double gyro_first_s = 0.0, gyro_last_s = 0.0;
  /// Accelerometer rows outside the gyroscope's span, dropped.
  std::size_t rows_dropped_before = 0;
  std::size_t rows_dropped_after = 0;
  /// The longest step between gyroscope samples within the overlap (s), and
  /// where it starts (s on the accelerometer's clock).
  double gyro_gap_s = 0.0;
  double gyro_gap_at_s = 0.0;
  std::vector<StreamFinding> findings;
};

/// Takes the three reading columns of `gyro_log` (read as an accelerometer
/// log: t, x, y, z) as the gyroscope of `recording`, in `units` (deg/s are
/// converted to rad/s; counts are kept).
///
/// When the two logs hold the same samples (as many rows, at the same times
/// within a hundredth of the sample period) they are taken row by row.
/// Otherwise the two streams are put on the accelerometer's stamps
/// (docs/method.md §7, "Two streams at two rates"): each row's gyroscope
/// reading is the mean, over the row's own interval (from the midpoint with
/// the row before to the midpoint with the row after), of the rate
/// interpolated linearly between the
/// gyroscope's samples, so that the angle the gyroscope turned through
/// between any two rows is kept; the accelerometer's readings stay as read.
/// Accelerometer rows outside the gyroscope's span are dropped. Times are
/// compared after adding each recording's time_origin_ns.
/// \throws mpcal::Error naming both sources when the spans do not overlap
///   (fewer than two accelerometer rows within the gyroscope's span), or
///   `recording` already has gyroscope readings.
StreamMerge MergeGyroLog(Recording& recording,
                         const Recording& gyro_log,
                         GyroUnits units);

/// A finding of MergeGyroLog in plain words, the streams named `accel` and
/// `gyro` (a path or a topic).
std::string Describe(StreamFinding finding,
                     const StreamMerge& merge,
                     const std::string& accel,
                     const std::string& gyro);

}  // namespace mpcal
