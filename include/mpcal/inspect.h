/// \file inspect.h
/// \brief What an input holds, before it is calibrated: a recording's
/// topics (bag.h) and, for each sensor_msgs/Imu topic, the range of its
/// readings; a text log's layout and the range of its rows. The ranges show
/// a wrong unit before a calibration fails on it: an accelerometer whose
/// magnitude is about 1 is in g, not m/s².
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mpcal/bag.h"
#include "mpcal/log_reader.h"
#include "mpcal/units.h"

namespace mpcal {

/// The range of a three-axis reading over a series, in the series' units.
struct ReadingRange {
  std::size_t count = 0;  ///< readings taken
  Eigen::Vector3d min = Eigen::Vector3d::Zero();
  Eigen::Vector3d max = Eigen::Vector3d::Zero();
  double norm_sum = 0.0;  ///< sum of the magnitudes
  /// Largest |component| over the axes and the readings.
  double largest_abs() const;
  /// Mean of the magnitudes (0 for no reading).
  double mean_norm() const;
  void Add(const Eigen::Vector3d& v);
};

/// What the magnitude of an accelerometer's readings says of their units,
/// judged as mpcal::CheckUnits judges a log before calibrating (the mean
/// magnitude against standard gravity, the band of plausible.h).
enum class AccelUnitsLook {
  kNotJudged,   ///< no readings, or raw counts (they have no fixed scale)
  kFits,        ///< the mean magnitude is within 0.5-1.6 g in the declared units
  kLikeG,       ///< declared m/s², the magnitude is about 1: g
  kLikeMps2,    ///< declared g, the magnitude is about 9.8: m/s²
  kLikeCounts,  ///< beyond 20 g: raw ADC counts
  kNeither,     ///< none of these: the columns or the units are wrong
};

/// What the largest reading of a gyroscope says of its units.
enum class GyroUnitsLook {
  kNotJudged,   ///< no readings, or raw counts
  kFits,        ///< within the largest MEMS full scale (4000 deg/s)
  kLikeDps,     ///< declared rad/s, beyond 70 rad/s but not beyond 4000 deg/s
  kLikeCounts,  ///< beyond 4000 deg/s in either reading
};

/// The judgements, from the ranges (exposed for tests and other callers).
AccelUnitsLook LookOfAccel(const ReadingRange& accel, AccelUnits declared);
GyroUnitsLook LookOfGyro(const ReadingRange& gyro, GyroUnits declared);

/// Messages in file order against a time: how many are earlier than a
/// message before them, and how far back the worst went. Counted as they
/// come (no message held), so duplicates are not told apart here.
struct TimeOrderCount {
  std::size_t out_of_order = 0;
  double worst_back_s = 0.0;
  void Add(std::int64_t time_ns);

 private:
  std::int64_t latest_ns_ = 0;
  bool any_ = false;
};

/// One sensor_msgs/Imu topic, read message by message.
struct ImuTopicInspection {
  std::string topic;
  std::size_t messages = 0;
  /// Earliest and latest header stamps (ns since the Unix epoch), and the
  /// mean rate they give: (messages - 1) / span.
  std::int64_t first_stamp_ns = 0;
  std::int64_t last_stamp_ns = 0;
  double rate_hz = 0.0;
  /// The header stamps and the receive times in file order.
  TimeOrderCount stamp_order;
  TimeOrderCount receive_order;
  /// In m/s² and rad/s, as ROS defines them; only the messages that give the
  /// quantity (covariance[0] not -1).
  ReadingRange accel_mps2;
  ReadingRange gyro_radps;
  AccelUnitsLook accel_look = AccelUnitsLook::kNotJudged;
  GyroUnitsLook gyro_look = GyroUnitsLook::kNotJudged;
};

/// A text log: the layout found and its rows.
struct LogInspection {
  LogLayout layout;
  AccelUnits units = AccelUnits::kMps2;  ///< as LogOptions declared them
  GyroUnits gyro_units = GyroUnits::kRadps;
  std::size_t rows = 0;
  /// First and last time (s, the log's own clock) and the mean rate.
  double first_time_s = 0.0;
  double last_time_s = 0.0;
  double rate_hz = 0.0;
  /// Rows whose time is not later than the row before (calibration refuses
  /// a log whose time goes back, and drops repeated times).
  std::size_t time_not_increasing = 0;
  /// In the log's units (`units`, `gyro_units`), not converted.
  ReadingRange accel;
  ReadingRange gyro;
  AccelUnitsLook accel_look = AccelUnitsLook::kNotJudged;
  GyroUnitsLook gyro_look = GyroUnitsLook::kNotJudged;
};

/// What Inspect found: a recording (`bag` filled) or a text log (`log`).
struct Inspection {
  std::string source;
  bool is_recording = false;
  BagSummary bag;                       ///< topics, compression, warnings
  std::vector<ImuTopicInspection> imu;  ///< each sensor_msgs/Imu topic
  LogInspection log;
  std::vector<std::string> warnings;  ///< the readers' non-fatal findings
};

/// The mean rate of a topic from its receive times: (messages - 1) / span;
/// 0 when it cannot be told.
double TopicRateHz(const BagTopic& topic);

/// Inspects `path`: a recording (every sensor_msgs/Imu topic read in full,
/// one pass each) or a text log (`options` as ReadLog takes them, read line
/// by line, nothing held).
/// \throws mpcal::Error as InspectBag and ReadImuMessages for a recording,
///   as LogScanner for a text log.
Inspection Inspect(const std::string& path, const LogOptions& options);

/// The inspection as JSON, `"format": "mpcal.inspection/1"`
/// (docs/schemas/mpcal.inspection-1.schema.json).
std::string InspectionJson(const Inspection& inspection);

}  // namespace mpcal
