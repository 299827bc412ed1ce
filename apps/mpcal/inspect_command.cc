// mpcal inspect: what a recording or a log holds, before calibrating it:
// topics, types, counts, rates, spans, compression, and the range of the
// readings, so that a wrong unit shows before a calibration fails on it.
#include <cmath>
#include <ctime>
#include <memory>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "cli_options.h"
#include "command.h"
#include "explain.h"
#include "mpcal/atomic_file.h"
#include "mpcal/count.h"
#include "mpcal/inspect.h"
#include "mpcal/log_reader.h"

namespace mpcal::cli {
namespace {

struct InspectFlags {
  std::string input;
  std::string json;
  LogOptions log;
};

std::string ContainerName(BagFormat format) {
  switch (format) {
    case BagFormat::kRos1:
      return "ROS 1 bag";
    case BagFormat::kMcap:
      return "MCAP file";
    case BagFormat::kRos2Sqlite:
      return "ROS 2 bag (SQLite)";
  }
  return "recording";
}

// "2023-11-14 22:13:20.002 UTC", or "-" for an unknown time.
std::string UtcTime(std::int64_t ns) {
  if (ns == 0) return "-";
  const std::int64_t s = ns >= 0 ? ns / 1000000000 : -((-ns + 999999999) / 1000000000);
  const auto ms = static_cast<int>((ns - s * 1000000000) / 1000000);
  const auto t = static_cast<std::time_t>(s);
  std::tm utc{};
  if (::gmtime_r(&t, &utc) == nullptr) return "-";
  return fmt::format("{:04}-{:02}-{:02} {:02}:{:02}:{:02}.{:03} UTC",
                     utc.tm_year + 1900,
                     utc.tm_mon + 1,
                     utc.tm_mday,
                     utc.tm_hour,
                     utc.tm_min,
                     utc.tm_sec,
                     ms);
}

std::string GyroSymbol(GyroUnits units) {
  switch (units) {
    case GyroUnits::kRadps:
      return "rad/s";
    case GyroUnits::kDps:
      return "deg/s";
    case GyroUnits::kCounts:
      return "counts";
  }
  return "";
}

double SpanS(std::int64_t first_ns, std::int64_t last_ns) {
  return static_cast<double>(static_cast<long double>(last_ns) -
                             static_cast<long double>(first_ns)) /
         1e9;
}

void PrintTopics(const BagSummary& bag) {
  std::size_t name_width = 5;
  std::size_t type_width = 4;
  for (const BagTopic& t : bag.topics) {
    name_width = std::max(name_width, t.name.size());
    type_width = std::max(type_width, t.type.size());
  }
  fmt::print("  {:<{}}  {:<{}}  {:>8}  {:>9}  {:>8}  first received\n",
             "topic",
             name_width,
             "type",
             type_width,
             "messages",
             "rate (Hz)",
             "span (s)");
  for (const BagTopic& t : bag.topics) {
    const double rate = TopicRateHz(t);
    fmt::print(
        "  {:<{}}  {:<{}}  {:>8}  {:>9}  {:>8}  {}\n",
        t.name,
        name_width,
        t.type,
        type_width,
        t.messages,
        rate > 0 ? fmt::format("{:.4g}", rate) : "-",
        t.first_ns != 0 ? fmt::format("{:.3f}", SpanS(t.first_ns, t.last_ns)) : "-",
        UtcTime(t.first_ns));
  }
}

std::string AxesLine(const ReadingRange& r) {
  return fmt::format("x {:.4g} to {:.4g}, y {:.4g} to {:.4g}, z {:.4g} to {:.4g}",
                     r.min.x(),
                     r.max.x(),
                     r.min.y(),
                     r.max.y(),
                     r.min.z(),
                     r.max.z());
}

// What the accelerometer's magnitude says, in the words of the input kind:
// a recording's units are fixed by ROS, a text log's are the --units given.
std::string AccelVerdict(AccelUnitsLook look, AccelUnits declared, bool recording) {
  const std::string unit(UnitSymbol(declared));
  const AccelUnits looks_like = look == AccelUnitsLook::kLikeG      ? AccelUnits::kG
                                : look == AccelUnitsLook::kLikeMps2 ? AccelUnits::kMps2
                                                                    : AccelUnits::kCounts;
  const std::string fix =
      recording ? std::string(
                      " (the driver does not publish m/s\u00b2 as "
                      "sensor_msgs/Imu asks)")
                : fmt::format(
                      " (give {} {})", FlagName(Option::kLogUnits), ToString(looks_like));
  switch (look) {
    case AccelUnitsLook::kNotJudged:
      return "";
    case AccelUnitsLook::kFits:
      return "fits " + unit;
    case AccelUnitsLook::kLikeG:
      return "about 1: the readings are in g, not " + unit + fix;
    case AccelUnitsLook::kLikeMps2:
      return "about 9.8: the readings are in m/s\u00b2, not g" + fix;
    case AccelUnitsLook::kLikeCounts:
      return "beyond 20 g: the readings look like raw ADC counts, not " + unit + fix;
    case AccelUnitsLook::kNeither:
      return "far from gravity in " + unit + " and in g: check the " +
             (recording ? std::string("driver") : "columns and the units");
  }
  return "";
}

std::string GyroVerdict(GyroUnitsLook look, GyroUnits declared, bool recording) {
  switch (look) {
    case GyroUnitsLook::kNotJudged:
      return "";
    case GyroUnitsLook::kFits:
      return "within the 4000 deg/s of any MEMS gyroscope";
    case GyroUnitsLook::kLikeDps:
      return "beyond the 4000 deg/s of any MEMS gyroscope in rad/s: the readings are in "
             "deg/s" +
             (recording ? std::string(" (the driver does not publish rad/s)")
                        : fmt::format(" (give {} dps)", FlagName(Option::kLogGyroUnits)));
    case GyroUnitsLook::kLikeCounts:
      return fmt::format(
          "beyond the 4000 deg/s of any MEMS gyroscope in {}: the readings look like raw "
          "ADC counts",
          GyroSymbol(declared));
  }
  return "";
}

void PrintRanges(const ReadingRange& accel,
                 const std::string& accel_unit,
                 const std::string& accel_verdict,
                 const ReadingRange& gyro,
                 const std::string& gyro_unit,
                 const std::string& gyro_verdict) {
  if (accel.count == 0) {
    fmt::print("  accelerometer: not measured (covariance[0] = -1)\n");
  } else {
    fmt::print("  accelerometer ({}): {}\n", accel_unit, AxesLine(accel));
    fmt::print("    mean magnitude {:.4g} {}: {}\n",
               accel.mean_norm(),
               accel_unit,
               accel_verdict);
  }
  if (gyro.count == 0) {
    fmt::print("  gyroscope: none\n");
  } else {
    fmt::print("  gyroscope ({}): {}\n", gyro_unit, AxesLine(gyro));
    fmt::print("    largest |reading| {:.4g} {}: {}\n",
               gyro.largest_abs(),
               gyro_unit,
               gyro_verdict);
  }
}

std::string OrderLine(const TimeOrderCount& order, bool chosen) {
  if (order.out_of_order == 0) return "in order";
  return fmt::format("{} out of order (the furthest {:.4g} ms back){}",
                     Count(order.out_of_order, "message"),
                     order.worst_back_s * 1e3,
                     chosen ? "; sorted when read" : "");
}

void PrintImuTopic(const ImuTopicInspection& t, RecordingTime chosen) {
  fmt::print("\n{}: {}, header stamps over {:.3f} s at {:.4g} Hz\n",
             t.topic,
             Count(t.messages, "message"),
             SpanS(t.first_stamp_ns, t.last_stamp_ns),
             t.rate_hz);
  PrintRanges(t.accel_mps2,
              "m/s\u00b2",
              AccelVerdict(t.accel_look, AccelUnits::kMps2, true),
              t.gyro_radps,
              "rad/s",
              GyroVerdict(t.gyro_look, GyroUnits::kRadps, true));
  fmt::print("  header stamps: {}\n",
             OrderLine(t.stamp_order, chosen == RecordingTime::kHeader));
  fmt::print("  receive times: {}\n",
             OrderLine(t.receive_order, chosen == RecordingTime::kReceive));
}

void PrintRecording(const Inspection& in, RecordingTime chosen) {
  const BagSummary& bag = in.bag;
  std::string compressions;
  for (const std::string& c : bag.compressions) {
    compressions += (compressions.empty() ? "" : ", ") + c;
  }
  fmt::print("{}: {}, {}{}\n",
             in.source,
             ContainerName(bag.format),
             Count(bag.topics.size(), "topic"),
             compressions.empty() ? "" : ", chunks " + compressions);
  if (!bag.topics.empty()) PrintTopics(bag);
  for (const ImuTopicInspection& t : in.imu) PrintImuTopic(t, chosen);
  if (in.imu.empty()) fmt::print("\nno sensor_msgs/Imu topic\n");
}

void PrintTextLog(const Inspection& in) {
  const LogInspection& log = in.log;
  fmt::print("{}: text log, {}, {:.4g} s at {:.4g} Hz\n",
             in.source,
             Count(log.rows, "row"),
             log.last_time_s - log.first_time_s,
             log.rate_hz);
  const LogLayout& l = log.layout;
  fmt::print("  columns: {}\n", l.Describe());
  fmt::print("  {}, time in {}{}\n",
             l.header_line > 0 ? fmt::format("header on line {}", l.header_line)
                               : std::string("no header"),
             l.time_column < 0 ? std::string("sample numbers") : ToString(l.time_unit),
             log.time_not_increasing > 0
                 ? fmt::format("; {} not later than the row before",
                               Count(log.time_not_increasing, "row"))
                 : "");
  PrintRanges(log.accel,
              std::string(UnitSymbol(log.units)),
              AccelVerdict(log.accel_look, log.units, false),
              log.gyro,
              GyroSymbol(log.gyro_units),
              GyroVerdict(log.gyro_look, log.gyro_units, false));
}

void Run(InspectFlags& f) {
  if (!f.json.empty()) CheckOutput(f.json, {f.input});
  const Inspection in = Inspect(f.input, f.log);
  if (in.is_recording) {
    PrintRecording(in, f.log.recording_time);
  } else {
    PrintTextLog(in);
  }
  for (const std::string& w : in.bag.warnings) fmt::print("  note: {}\n", w);
  for (const std::string& w : in.warnings) fmt::print("  note: {}\n", w);
  if (!f.json.empty()) {
    WriteFileAtomically(f.json, InspectionJson(in));
    fmt::print("\nwrote {}\n", f.json);
  }
}

}  // namespace

void AddInspectCommand(CLI::App& root) {
  auto flags = std::make_shared<InspectFlags>();
  CLI::App* app = root.add_subcommand(
      "inspect",
      "Show what a recording or a log holds before calibrating it: a ROS bag's, MCAP "
      "file's or ROS 2 bag's topics, types, message counts, rates, spans and "
      "compression, and for each sensor_msgs/Imu topic the range of its readings; a "
      "text log's columns, rows, rate and ranges; says when the readings' magnitude "
      "does not fit their units");
  app->add_option("INPUT",
                  flags->input,
                  "Recording (ROS 1 bag, MCAP, ROS 2 bag directory) or log (CSV or text, "
                  "'-' for standard input)")
      ->check(InputPath)
      ->required();
  app->add_option(
         "--json", flags->json, "Also write the facts as JSON (mpcal.inspection/1)")
      ->check(OutputPath);
  AddLogOptions(*app, flags->log);
  app->footer(
      "Examples:\n"
      "  mpcal inspect session.bag\n"
      "  mpcal inspect rosbag2_dir/ --topic /imu/data --json facts.json\n"
      "  mpcal inspect session.csv --units g");
  app->callback([flags] { Run(*flags); });
}

}  // namespace mpcal::cli
