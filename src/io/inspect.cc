// What an input holds: a recording's topics and its IMU topics' readings, or
// a text log's layout and rows; each read once, nothing held.
#include "mpcal/inspect.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <span>
#include <string>

#include "bag_log.h"
#include "mpcal/error.h"
#include "mpcal/plausible.h"

namespace mpcal {
namespace {

constexpr double kInspectNsPerS = 1e9;

bool IsImuTopicType(const std::string& type) {
  return type == "sensor_msgs/Imu" || type == "sensor_msgs/msg/Imu";
}

double RateOf(std::size_t count, double span_s) {
  return count > 1 && span_s > 0.0 ? static_cast<double>(count - 1) / span_s : 0.0;
}

ImuTopicInspection InspectImuTopic(const std::string& path,
                                   const std::string& topic,
                                   std::vector<std::string>& warnings) {
  ImuTopicInspection t;
  t.topic = topic;
  t.first_stamp_ns = std::numeric_limits<std::int64_t>::max();
  t.last_stamp_ns = std::numeric_limits<std::int64_t>::min();
  ReadImuMessages(
      path,
      topic,
      [&t](std::span<const ImuMessage> batch) {
        for (const ImuMessage& m : batch) {
          ++t.messages;
          t.first_stamp_ns = std::min(t.first_stamp_ns, m.stamp_ns);
          t.last_stamp_ns = std::max(t.last_stamp_ns, m.stamp_ns);
          t.stamp_order.Add(m.stamp_ns);
          t.receive_order.Add(m.receive_ns);
          if (m.has_linear_acceleration) t.accel_mps2.Add(m.linear_acceleration_mps2);
          if (m.has_angular_velocity) t.gyro_radps.Add(m.angular_velocity_radps);
        }
      },
      warnings);
  if (t.messages == 0) {
    t.first_stamp_ns = t.last_stamp_ns = 0;
  } else {
    // In long double: the span of two int64 stamps may not fit an int64.
    const long double span_ns = static_cast<long double>(t.last_stamp_ns) -
                                static_cast<long double>(t.first_stamp_ns);
    t.rate_hz = RateOf(t.messages, static_cast<double>(span_ns / kInspectNsPerS));
  }
  t.accel_look = LookOfAccel(t.accel_mps2, AccelUnits::kMps2);
  t.gyro_look = LookOfGyro(t.gyro_radps, GyroUnits::kRadps);
  return t;
}

void InspectRecording(const std::string& path,
                      const std::string& topic,
                      Inspection& out) {
  out.is_recording = true;
  out.bag = InspectBag(path);
  if (!topic.empty()) {
    // The one asked for: ReadImuMessages refuses it, by name, when absent or
    // of another type.
    out.imu.push_back(InspectImuTopic(path, topic, out.warnings));
    return;
  }
  for (const BagTopic& t : out.bag.topics) {
    if (IsImuTopicType(t.type)) {
      out.imu.push_back(InspectImuTopic(path, t.name, out.warnings));
    }
  }
}

void InspectTextLog(const std::string& path, const LogOptions& options, Inspection& out) {
  LogScanner scanner(path, options, /*parse_gyro=*/true);
  LogInspection& log = out.log;
  log.layout = scanner.layout();
  log.units = options.units;
  log.gyro_units = options.gyro_units();
  const double per_unit = log.layout.seconds_per_time_unit;
  double previous_s = 0.0;
  LogLine line;
  while (scanner.Next(&line)) {
    if (!line.is_data) continue;
    const double t_s = line.time_raw * per_unit;
    if (log.rows == 0) {
      log.first_time_s = t_s;
    } else if (!(t_s > previous_s)) {
      ++log.time_not_increasing;
    }
    previous_s = t_s;
    log.last_time_s = t_s;
    ++log.rows;
    log.accel.Add(line.accel);
    if (log.layout.has_gyro()) log.gyro.Add(line.gyro);
  }
  out.source = scanner.source();
  out.warnings = scanner.warnings();
  log.rate_hz = RateOf(log.rows, log.last_time_s - log.first_time_s);
  log.accel_look = LookOfAccel(log.accel, log.units);
  log.gyro_look = LookOfGyro(log.gyro, log.gyro_units);
}

}  // namespace

double ReadingRange::largest_abs() const {
  return count == 0 ? 0.0
                    : std::max(min.cwiseAbs().maxCoeff(), max.cwiseAbs().maxCoeff());
}

double ReadingRange::mean_norm() const {
  return count == 0 ? 0.0 : norm_sum / static_cast<double>(count);
}

void ReadingRange::Add(const Eigen::Vector3d& v) {
  min = count == 0 ? v : Eigen::Vector3d(min.cwiseMin(v));
  max = count == 0 ? v : Eigen::Vector3d(max.cwiseMax(v));
  norm_sum += v.norm();
  ++count;
}

// CheckUnits' rule (src/solve/units_check.cc) on the mean magnitude: within
// the plausible band of gravity the units fit; about 1 read as m/s² is g,
// about 9.8 read as g is m/s², beyond 20 g raw counts.
AccelUnitsLook LookOfAccel(const ReadingRange& accel, AccelUnits declared) {
  const std::optional<double> per_unit = FixedMps2PerUnit(declared);
  if (accel.count == 0 || !per_unit) return AccelUnitsLook::kNotJudged;
  const double mean = accel.mean_norm();
  const double ratio = mean * *per_unit / kStandardGravityMps2;
  if (ratio >= kPlausibleRestRatioLow && ratio <= kPlausibleRestRatioHigh) {
    return AccelUnitsLook::kFits;
  }
  if (declared == AccelUnits::kMps2 && std::abs(mean - 1.0) < 0.5) {
    return AccelUnitsLook::kLikeG;
  }
  if (declared == AccelUnits::kG && std::abs(mean / kStandardGravityMps2 - 1.0) < 0.5) {
    return AccelUnitsLook::kLikeMps2;
  }
  if (ratio > 20.0) return AccelUnitsLook::kLikeCounts;
  return AccelUnitsLook::kNeither;
}

// CheckUnits' gyroscope rule: beyond the largest MEMS full scale.
GyroUnitsLook LookOfGyro(const ReadingRange& gyro, GyroUnits declared) {
  if (gyro.count == 0 || declared == GyroUnits::kCounts) return GyroUnitsLook::kNotJudged;
  const double to_radps = declared == GyroUnits::kDps ? std::numbers::pi / 180.0 : 1.0;
  const double largest_radps = gyro.largest_abs() * to_radps;
  if (!(largest_radps > kMaxGyroRateRadps)) return GyroUnitsLook::kFits;
  if (declared == GyroUnits::kRadps &&
      largest_radps * std::numbers::pi / 180.0 <= kMaxGyroRateRadps) {
    return GyroUnitsLook::kLikeDps;
  }
  return GyroUnitsLook::kLikeCounts;
}

void TimeOrderCount::Add(std::int64_t time_ns) {
  if (any_ && time_ns < latest_ns_) {
    ++out_of_order;
    const long double back_ns =
        static_cast<long double>(latest_ns_) - static_cast<long double>(time_ns);
    worst_back_s = std::max(worst_back_s, static_cast<double>(back_ns / kInspectNsPerS));
    return;
  }
  latest_ns_ = time_ns;
  any_ = true;
}

double TopicRateHz(const BagTopic& topic) {
  if (topic.messages < 2 || topic.last_ns <= topic.first_ns) return 0.0;
  const long double span_ns =
      static_cast<long double>(topic.last_ns) - static_cast<long double>(topic.first_ns);
  return RateOf(static_cast<std::size_t>(topic.messages),
                static_cast<double>(span_ns / kInspectNsPerS));
}

Inspection Inspect(const std::string& path, const LogOptions& options) {
  Inspection out;
  out.source = path;
  if (IsBag(path)) {
    logio::RefuseTextOptions(path, options);
    InspectRecording(path, options.topic, out);
  } else {
    InspectTextLog(path, options, out);
  }
  return out;
}

}  // namespace mpcal
