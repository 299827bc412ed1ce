#include "bag_log.h"

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "chunk_source.h"
#include "log_text.h"
#include "mpcal/bag.h"
#include "mpcal/error.h"
#include "row_sink.h"
#include "time_order.h"

namespace mpcal::logio {
namespace {

constexpr double kNsPerS = 1e9;

bool IsImuType(const std::string& type) {
  return type == "sensor_msgs/Imu" || type == "sensor_msgs/msg/Imu";
}

// The topic to read, and how many messages the recording's index says it
// holds (0 when unknown: a topic given by name is read without looking, and
// a ROS 2 bag's SQLite files count them only by a pass over every message).
struct ChosenTopic {
  std::string name;
  std::int64_t messages = 0;
};

ChosenTopic ChooseTopic(const std::string& path, const LogOptions& options) {
  if (!options.topic.empty()) return {options.topic, 0};
  const std::vector<BagTopic> topics = ListBagTopics(path);
  std::vector<std::string> imu;
  std::string all;
  std::int64_t messages = 0;
  for (const BagTopic& t : topics) {
    if (IsImuType(t.type)) {
      imu.push_back(t.name);
      messages = t.messages;
    }
    all += (all.empty() ? "" : ", ") + t.name + " (" + t.type + ")";
  }
  if (imu.size() == 1) return {imu.front(), messages};
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

}  // namespace

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
                    "and time (the header stamp or the receive time); columns, units, "
                    "time unit and rate "
                    "are for text logs only");
  }
}

namespace {

[[noreturn]] void ThrowNotMeasured(const std::string& path,
                                   const std::string& topic,
                                   bool gyro_only) {
  throw Error(ErrorKind::kInput,
              path + ": topic '" + topic + "' gives no " +
                  (gyro_only ? "angular velocity" : "linear acceleration") +
                  " (its covariance starts with -1: not measured)");
}

// Two int64 ns times whose difference overflows are not times.
[[noreturn]] void ThrowTimesApart(const std::string& path, const std::string& topic) {
  throw Error(ErrorKind::kTime,
              path + ": topic '" + topic +
                  "' has message times more than 292 years apart: not times");
}

// The messages of the topic as rows, in file order: time in ns from the
// first message's (exact in a double up to 2^53 ns, 104 days; sorting does
// not need more), the readings as they are.
struct HeldRows {
  ChunkRows rows;
  bool gyro = true;           // as the first message says, for every row
  std::int64_t first_ns = 0;  // the first message's time, the rows' origin
};

// The rows to make room for at once: the messages the index counts, but
// never more than the recording's bytes can hold (a sensor_msgs/Imu is 37
// doubles, 296 bytes and more, in any of its serialisations), so that a
// damaged count cannot claim memory. Room made at once rather than by
// doubling spares the copies and the pages each doubling touches and frees,
// which on a million messages cost as much as their decoding.
std::size_t RowsToReserve(const std::string& path, std::int64_t messages) {
  constexpr std::uintmax_t kSmallestImuBytes = 296;
  if (messages <= 0) return 0;
  std::error_code ec;
  std::uintmax_t bytes = 0;
  if (std::filesystem::is_directory(path, ec)) {
    for (const auto& entry : std::filesystem::directory_iterator(path, ec)) {
      if (entry.is_regular_file(ec)) bytes += entry.file_size(ec);
    }
  } else {
    bytes = std::filesystem::file_size(path, ec);
  }
  if (ec) return 0;
  return static_cast<std::size_t>(std::min<std::uintmax_t>(
      static_cast<std::uintmax_t>(messages), bytes / kSmallestImuBytes));
}

// A gyroscope's own stream (`gyro_only`, gyro_log.h): its rates take the
// accelerometer's place, as a gyroscope log's columns do.
HeldRows ReadMessages(const std::string& path,
                      const std::string& topic,
                      RecordingTime time,
                      bool gyro_only,
                      std::size_t expected_rows,
                      std::vector<std::string>& warnings) {
  HeldRows held;
  held.rows.time.reserve(expected_rows);
  held.rows.accel.reserve(expected_rows);
  std::int64_t first_ns = 0;
  bool first = true;
  ReadImuMessages(
      path,
      topic,
      [&](std::span<const ImuMessage> batch) {
        for (const ImuMessage& m : batch) {
          const std::int64_t t_ns =
              time == RecordingTime::kReceive ? m.receive_ns : m.stamp_ns;
          if (first) {
            const bool wanted =
                gyro_only ? m.has_angular_velocity : m.has_linear_acceleration;
            if (!wanted) ThrowNotMeasured(path, topic, gyro_only);
            first_ns = t_ns, first = false;
            held.first_ns = first_ns;
            held.gyro = !gyro_only && m.has_angular_velocity;
            if (held.gyro) held.rows.gyro.reserve(expected_rows);
          }
          std::int64_t offset_ns = 0;
          if (__builtin_sub_overflow(t_ns, first_ns, &offset_ns)) {
            ThrowTimesApart(path, topic);
          }
          held.rows.time.push_back(static_cast<double>(offset_ns));
          held.rows.accel.push_back(gyro_only ? m.angular_velocity_radps
                                              : m.linear_acceleration_mps2);
          if (held.gyro) held.rows.gyro.push_back(m.angular_velocity_radps);
        }
      },
      warnings);
  return held;
}

// Seconds from the earliest message's time (the first row's once sorted):
// the difference of two whole numbers of ns is exact, so a recording in
// order gets the times a text log of its stamps in seconds would.
void ToSecondsFromFirst(std::vector<double>& time_ns) {
  if (time_ns.empty()) return;
  const double origin_ns = time_ns.front();
  for (double& t : time_ns) t = (t - origin_ns) / kNsPerS;
}

// Streaming: the sorted rows handed to the sink a piece at a time, as a
// text log's chunks are.
void HandOverInPieces(RowSink& sink, const ChunkRows& all) {
  constexpr std::size_t kPieceRows = 1 << 16;
  ChunkRows piece;
  for (std::size_t begin = 0; begin < all.time.size(); begin += kPieceRows) {
    const std::size_t end = std::min(all.time.size(), begin + kPieceRows);
    const auto b = static_cast<std::ptrdiff_t>(begin);
    const auto e = static_cast<std::ptrdiff_t>(end);
    piece.time.assign(all.time.begin() + b, all.time.begin() + e);
    piece.accel.assign(all.accel.begin() + b, all.accel.begin() + e);
    if (!all.gyro.empty()) piece.gyro.assign(all.gyro.begin() + b, all.gyro.begin() + e);
    piece.lines = end - begin;
    piece.last_row_line = end - begin;
    piece.has_content = true;
    sink.Append(piece);
  }
}

}  // namespace

LogStreamSummary ReadBagRows(const std::string& path,
                             const LogOptions& options,
                             Recording* rec,
                             std::function<void(const Recording&)> consume) {
  RefuseTextOptions(path, options);
  const ChosenTopic chosen = ChooseTopic(path, options);
  const std::string& topic = chosen.name;
  rec->units = AccelUnits::kMps2;
  rec->gyro_units = GyroUnits::kRadps;
  rec->source = path;
  std::vector<std::string> warnings;
  HeldRows held = ReadMessages(path,
                               topic,
                               options.recording_time,
                               options.gyroscope_only,
                               RowsToReserve(path, chosen.messages),
                               warnings);
  StampOrder order = SortByTime(held.rows.time, held.rows.accel, held.rows.gyro);
  order.worst_back_s /= kNsPerS;  // sorted in ns
  // The earliest time, so that two topics of one recording share a clock.
  if (!held.rows.time.empty()) {
    rec->time_origin_ns =
        held.first_ns + static_cast<std::int64_t>(held.rows.time.front());
  }
  ToSecondsFromFirst(held.rows.time);
  held.rows.lines = held.rows.time.size();
  held.rows.last_row_line = held.rows.lines;
  held.rows.has_content = !held.rows.time.empty();

  RowSink sink(rec, 1.0, /*index_time=*/false, /*line_base=*/0, /*total_bytes=*/0);
  sink.NameRows("message");
  const bool streaming = static_cast<bool>(consume);
  if (streaming) {
    sink.StreamTo(std::move(consume));
    HandOverInPieces(sink, held.rows);
  } else {
    sink.Adopt(std::move(held.rows));
  }
  const bool gyro = held.gyro;
  held = HeldRows{};  // the rows handed over: their memory back before Finish
  const std::string said = DescribeStampOrder(order, path);
  if (!said.empty()) warnings.push_back(said);
  rec->warnings.insert(rec->warnings.begin(), warnings.begin(), warnings.end());
  rec->stamp_order = order;
  sink.Finish(/*has_header=*/false);

  LogStreamSummary summary;
  summary.source = rec->source;
  summary.rows = sink.rows();
  summary.first_time_s = sink.first_time_s();
  summary.last_time_s = sink.last_time_s();
  summary.has_gyro = gyro && summary.rows > 0;
  summary.stamp_order = order;
  return summary;
}

}  // namespace mpcal::logio
