#include "bag_log.h"

#include <string>
#include <vector>

#include "chunk_source.h"
#include "log_text.h"
#include "mpcal/bag.h"
#include "mpcal/error.h"
#include "row_sink.h"

namespace mpcal::logio {
namespace {

constexpr double kNsPerS = 1e9;

bool IsImuType(const std::string& type) {
  return type == "sensor_msgs/Imu" || type == "sensor_msgs/msg/Imu";
}

std::string ChooseTopic(const std::string& path, const LogOptions& options) {
  if (!options.topic.empty()) return options.topic;
  const BagSummary summary = InspectBag(path);
  std::vector<std::string> imu;
  std::string all;
  for (const BagTopic& t : summary.topics) {
    if (IsImuType(t.type)) imu.push_back(t.name);
    all += (all.empty() ? "" : ", ") + t.name + " (" + t.type + ")";
  }
  if (imu.size() == 1) return imu.front();
  if (imu.empty()) {
    throw Error(ErrorKind::kInput,
                path + ": no sensor_msgs/Imu topic; the recording holds " +
                    (all.empty() ? std::string("none") : all));
  }
  std::string names;
  for (const std::string& n : imu) names += (names.empty() ? "" : ", ") + n;
  throw Error(ErrorKind::kOption,
              path + ": " + std::to_string(imu.size()) + " sensor_msgs/Imu topics (" +
                  names + "); one must be chosen",
              Give({{Option::kLogTopic, ""}}));
}

// A recording carries its own units (m/s², rad/s) and time: the options
// that describe a text log's columns would be silently wrong here.
void RefuseTextOptions(const std::string& path, const LogOptions& options) {
  const bool text_options =
      !options.columns.empty() || options.units != AccelUnits::kMps2 ||
      options.gyro_in_dps || options.gyro_in_counts ||
      options.time_unit != TimeUnit::kAuto || options.rate_hz != 0.0;
  if (text_options) {
    throw Error(ErrorKind::kOption,
                path +
                    ": a recording's sensor_msgs/Imu has its own units (m/s2, rad/s) "
                    "and time (the header stamp); columns, units, time unit and rate "
                    "are for text logs only");
  }
}

[[noreturn]] void ThrowNotMeasured(const std::string& path,
                                   const std::string& topic,
                                   bool gyro_only) {
  throw Error(ErrorKind::kInput,
              path + ": topic '" + topic + "' gives no " +
                  (gyro_only ? "angular velocity" : "linear acceleration") +
                  " (its covariance starts with -1: not measured)");
}

}  // namespace

LogStreamSummary ReadBagRows(const std::string& path,
                             const LogOptions& options,
                             Recording* rec,
                             std::function<void(const Recording&)> consume) {
  RefuseTextOptions(path, options);
  const std::string topic = ChooseTopic(path, options);
  rec->units = AccelUnits::kMps2;
  rec->gyro_units = GyroUnits::kRadps;
  rec->source = path;
  RowSink sink(rec, 1.0, /*index_time=*/false, /*line_base=*/0, /*total_bytes=*/0);
  sink.NameRows("message");
  if (consume) sink.StreamTo(std::move(consume));
  std::int64_t first_ns = 0;
  bool first = true;
  const bool gyro_only = options.gyroscope_only;
  bool gyro = true;  // as the first message says, for every row
  ChunkRows rows;
  std::string lines;  // one line per message, for the sink's message numbers
  std::vector<std::string> warnings;
  ReadImuMessages(
      path,
      topic,
      [&](std::span<const ImuMessage> batch) {
        rows.time.clear(), rows.accel.clear(), rows.gyro.clear();
        for (const ImuMessage& m : batch) {
          if (first) {
            const bool wanted =
                gyro_only ? m.has_angular_velocity : m.has_linear_acceleration;
            if (!wanted) ThrowNotMeasured(path, topic, gyro_only);
            first_ns = m.stamp_ns, first = false;
            gyro = !gyro_only && m.has_angular_velocity;
            rec->time_origin_ns = first_ns;
          }
          rows.time.push_back(static_cast<double>(m.stamp_ns - first_ns) / kNsPerS);
          // A gyroscope's own stream (gyro_log.h): its rates take the
          // accelerometer's place, as a gyroscope log's columns do.
          rows.accel.push_back(gyro_only ? m.angular_velocity_radps
                                         : m.linear_acceleration_mps2);
          if (gyro) rows.gyro.push_back(m.angular_velocity_radps);
        }
        lines.assign(2 * batch.size(), 'm');
        for (std::size_t i = 1; i < lines.size(); i += 2) lines[i] = '\n';
        rows.bytes = lines;
        rows.lines = batch.size();
        rows.last_row_line = batch.size();
        rows.has_content = true;
        sink.Append(rows);
      },
      warnings);
  rec->warnings.insert(rec->warnings.begin(), warnings.begin(), warnings.end());
  sink.Finish(/*has_header=*/false);

  LogStreamSummary summary;
  summary.source = rec->source;
  summary.rows = sink.rows();
  summary.first_time_s = sink.first_time_s();
  summary.last_time_s = sink.last_time_s();
  summary.has_gyro = gyro && summary.rows > 0;
  return summary;
}

}  // namespace mpcal::logio
