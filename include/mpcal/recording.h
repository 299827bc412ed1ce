/// \file recording.h
/// \brief An accelerometer recording in memory: time and readings.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mpcal/units.h"

namespace mpcal {

/// How the messages of a recording (bag.h) were ordered in time in the
/// file. Their rows are put in time order (a stable sort: messages at one
/// time keep their file order) and one row is kept per time; what that
/// changed is counted here.
struct StampOrder {
  /// Messages whose time is earlier than that of a message before them in
  /// the file.
  std::size_t out_of_order = 0;
  /// How far the worst of them went back: the latest time before it in the
  /// file minus its own (s).
  double worst_back_s = 0.0;
  /// Messages with the time and the readings of the one kept at that time
  /// (a message recorded twice): dropped.
  std::size_t duplicated = 0;
  /// Messages with the time of the one kept but other readings: dropped,
  /// the first in the file kept (src/io/time_order.cc says why).
  std::size_t same_time_other_readings = 0;

  bool changed() const {
    return out_of_order > 0 || duplicated > 0 || same_time_other_readings > 0;
  }
};

/// One log, as read. Readings stay in the log's units (`units`) so that raw
/// counts can be calibrated without a guessed scale; `time_s` is seconds from
/// an arbitrary origin (the log's own clock), strictly increasing after
/// reading (duplicates are reported and dropped by the reader).
struct Recording {
  std::vector<double> time_s;
  /// The log's clock at time_s = 0, ns: a robotics recording's first header
  /// stamp (ns since the Unix epoch; its times are counted from it), 0 for a
  /// text log (its times are its own clock). Two recordings' times compare
  /// after adding it.
  std::int64_t time_origin_ns = 0;
  /// Accelerometer readings (x, y, z) in `units`.
  std::vector<Eigen::Vector3d> accel;
  /// Gyroscope readings (rad/s); empty when the log has none. Raw counts
  /// when `gyro_units` is GyroUnits::kCounts (their scale is found from the
  /// session's turns).
  std::vector<Eigen::Vector3d> gyro_radps;
  /// A gyroscope recorded apart at its own stamps (MergeGyroLog): its
  /// samples as read, times in s on this recording's clock, readings in
  /// `gyro_units`. The turns are integrated over these and the noise at
  /// rest is measured on them; `gyro_radps` then holds their means over each
  /// row's interval. Empty when the gyroscope came on the rows.
  std::vector<double> gyro_samples_time_s;
  std::vector<Eigen::Vector3d> gyro_samples;
  /// kRadps for readings in rad/s (logs in deg/s are converted on reading),
  /// kCounts for raw counts.
  GyroUnits gyro_units = GyroUnits::kRadps;
  /// Units of the gyroscope columns as the log writes them: kDps for a log
  /// in deg/s (held in rad/s above), else as `gyro_units`. A calibration
  /// made from the recording records them, so that it applies to logs as
  /// they are written.
  GyroUnits gyro_log_units = GyroUnits::kRadps;
  AccelUnits units = AccelUnits::kMps2;
  /// Where it came from (file name, or "<simulated>"), for messages.
  std::string source;
  /// Non-fatal findings of the reader (gaps, duplicates, truncated last line).
  std::vector<std::string> warnings;
  /// A recording's (bag.h) messages put in time order: what that changed
  /// (one of `warnings` says it in words). Zero for a text log, whose rows
  /// must be in time order.
  StampOrder stamp_order;

  std::size_t size() const { return time_s.size(); }
  bool empty() const { return time_s.empty(); }
};

}  // namespace mpcal
