#include "cli_options.h"

#include <cmath>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "explain.h"
#include "mpcal/count.h"
#include "mpcal/error.h"
#include "mpcal/gravity.h"
#include "mpcal/gyro_log.h"
#include "mpcal/plausible.h"

namespace mpcal::cli {
namespace {

// A number flag: a finite value for which `ok` holds, else "must be
// `wanted`, got 'TEXT'" (CLI11's own checks print their range digit by digit).
template <typename Ok>
CLI::Validator FiniteNumberThat(Ok ok, std::string wanted, std::string type_name) {
  return CLI::Validator(
      [ok, wanted = std::move(wanted)](std::string& text) -> std::string {
        double v = 0.0;
        if (CLI::detail::lexical_cast(text, v) && std::isfinite(v) && ok(v)) return "";
        return fmt::format("must be {}, got '{}'", wanted, text);
      },
      std::move(type_name));
}

// A path flag: not empty, else `problem` (a shell variable never set is a
// slip, not a request to read or write nothing).
CLI::Validator NonEmpty(std::string problem, std::string type_name) {
  return CLI::Validator(
      [problem = std::move(problem)](const std::string& text) -> std::string {
        return text.empty() ? problem : "";
      },
      std::move(type_name));
}

}  // namespace

const CLI::Validator PositiveNumber =
    FiniteNumberThat([](double v) { return v > 0.0; }, "a positive number", "POSITIVE");
const CLI::Validator NonNegativeNumber = FiniteNumberThat(
    [](double v) { return v >= 0.0; }, "a positive (or zero) number", "NONNEGATIVE");

CLI::Validator NumberIn(double lo, double hi) {
  return FiniteNumberThat([lo, hi](double v) { return v >= lo && v <= hi; },
                          fmt::format("a number in [{}, {}]", lo, hi),
                          fmt::format("FLOAT in [{} - {}]", lo, hi));
}

const CLI::Validator FiniteNumber =
    FiniteNumberThat([](double) { return true; }, "a finite number", "FLOAT");
const CLI::Validator OutputPath =
    NonEmpty("the file name is empty; give a path, or '-' for standard output", "PATH");
const CLI::Validator OutputDirectory = NonEmpty(
    "the directory name is empty; give a path, or '.' for the current directory", "DIR");
const CLI::Validator InputPath =
    NonEmpty("the file name is empty; give a path, or '-' for standard input", "PATH");

void AddLogOptions(CLI::App& app, LogOptions& options, const CountsHelp& counts) {
  const std::vector<std::pair<std::string, AccelUnits>> units{
      {"mps2", AccelUnits::kMps2},
      {"g", AccelUnits::kG},
      {"counts", AccelUnits::kCounts}};
  const std::vector<std::pair<std::string, TimeUnit>> time_units{
      {"auto", TimeUnit::kAuto},
      {"s", TimeUnit::kSeconds},
      {"ms", TimeUnit::kMilliseconds},
      {"us", TimeUnit::kMicroseconds},
      {"ns", TimeUnit::kNanoseconds},
      {"index", TimeUnit::kSampleIndex}};
  app.add_option(std::string(FlagName(Option::kLogColumns)),
                 options.columns,
                 "Column mapping t=NAME|INDEX,ax=..,ay=..,az=..[,gx=..,gy=..,gz=..] "
                 "(0-based indices); default: from the header, else t,ax,ay,az")
      ->group("Input log");
  app.add_option(std::string(FlagName(Option::kLogUnits)),
                 options.units,
                 fmt::format("Accelerometer units in the log: mps2, g (9.80665 m/s2) or "
                             "counts ({})",
                             counts.accel))
      ->transform(OneOf(units))
      ->default_str("mps2")
      ->group("Input log");
  app.add_option(std::string(FlagName(Option::kLogTimeUnit)),
                 options.time_unit,
                 "Unit of the time column: s, ms, us, ns, index (sample number, "
                 "needs --rate) or auto (integers: detected from the spacing)")
      ->transform(OneOf(time_units))
      ->default_str("auto")
      ->group("Input log");
  app.add_option(std::string(FlagName(Option::kLogRate)),
                 options.rate_hz,
                 "Sample rate (Hz) when the time column is a sample index or absent")
      ->check(PositiveNumber)
      ->group("Input log");
  const std::vector<std::pair<std::string, std::string>> gyro_units{{"rads", "rads"},
                                                                    {"rad/s", "rads"},
                                                                    {"dps", "dps"},
                                                                    {"deg/s", "dps"},
                                                                    {"counts", "counts"}};
  app.add_option_function<std::string>(
         std::string(FlagName(Option::kLogGyroUnits)),
         [&options](const std::string& unit) {
           options.gyro_in_dps = unit == "dps";
           options.gyro_in_counts = unit == "counts";
         },
         fmt::format("Units of the gyroscope columns: rads (rad/s, the default), dps "
                     "(deg/s) or counts ({})",
                     counts.gyro))
      ->transform(OneOf(gyro_units))
      ->default_str("rads")
      ->group("Input log");
  app.add_option(std::string(FlagName(Option::kLogTopic)),
                 options.topic,
                 "The sensor_msgs/Imu topic when the input is a ROS 1 bag, an MCAP file "
                 "or a ROS 2 bag directory; default: its only IMU topic")
      ->group("Input log");
  const std::vector<std::pair<std::string, RecordingTime>> times{
      {"header", RecordingTime::kHeader}, {"receive", RecordingTime::kReceive}};
  app.add_option(std::string(FlagName(Option::kLogRecordingTime)),
                 options.recording_time,
                 "A recording's message time: header (the header stamp) or receive "
                 "(when the recorder received it); messages out of order are sorted "
                 "and counted")
      ->transform(OneOf(times))
      ->default_str("header")
      ->group("Input log");
}

void AddGyroLogOptions(CLI::App& app, GyroLogFlags& flags) {
  CLI::Option* log =
      app.add_option(std::string(FlagName(Option::kGyroLog)),
                     flags.path,
                     "The gyroscope in a file (or recording) of its own, in "
                     "--gyro-units: a time column and three readings, named by its "
                     "header (t, gx/gyr_x/wx/x, ...) or --gyro-columns, else t, x, y, z "
                     "in order; the same rows as the log, or its own rate and stamps "
                     "(then averaged onto the log's rows)")
          ->check(InputPath)
          ->group("Input log");
  app.add_option(std::string(FlagName(Option::kGyroLogColumns)),
                 flags.columns,
                 "Column mapping of the --gyro-log file t=NAME|INDEX,gx=..,gy=..,gz=.. "
                 "(0-based indices); default: from its header, else t, x, y, z")
      ->needs(log)
      ->group("Input log");
  CLI::Option* accel =
      app.add_option(std::string(FlagName(Option::kAccelTopic)),
                     flags.accel_topic,
                     "The accelerometer's sensor_msgs/Imu topic when the recording "
                     "publishes the sensors apart (its angular velocity is not used)")
          ->group("Input log");
  app.add_option(std::string(FlagName(Option::kGyroTopic)),
                 flags.gyro_topic,
                 "The gyroscope's sensor_msgs/Imu topic (in the input recording, or in "
                 "--gyro-log's), at its own rate and stamps: averaged onto the "
                 "accelerometer's messages")
      ->group("Input log");
  if (CLI::Option* topic =
          app.get_option_no_throw(std::string(FlagName(Option::kLogTopic)))) {
    accel->excludes(topic);
  }
}

LogOptions WithAccelTopic(LogOptions log, const GyroLogFlags& flags) {
  if (!flags.accel_topic.empty()) log.topic = flags.accel_topic;
  return log;
}

MergedStreams MergeGyroLogFile(Recording& recording,
                               const std::string& input,
                               const GyroLogFlags& flags,
                               const LogOptions& log) {
  if (!flags.given()) return {};
  LogOptions options;
  options.columns = flags.columns;
  options.time_unit = log.time_unit;
  options.rate_hz = log.rate_hz;
  options.gyro_in_dps = log.gyro_in_dps;
  options.gyro_in_counts = log.gyro_in_counts;
  options.topic = flags.gyro_topic;
  // A bag's two streams on one clock: the one --time chose.
  options.recording_time = log.recording_time;
  const std::string path = flags.path.empty() ? input : flags.path;
  const Recording gyro = ReadGyroLog(path, options);
  // The gyroscope's own stream replaces whatever rates the accelerometer's
  // messages carry (a driver's accelerometer topic may fill them with zeros).
  if (!flags.gyro_topic.empty()) recording.gyro_radps.clear();
  const std::size_t accel_rows = recording.size();
  const StreamMerge m = MergeGyroLog(recording, gyro, log.gyro_units());
  MergedStreams out;
  out.warnings = gyro.warnings;
  const std::string accel_name =
      flags.gyro_topic.empty() ? recording.source : WithAccelTopic(log, flags).topic;
  const std::string gyro_name = flags.gyro_topic.empty() ? gyro.source : flags.gyro_topic;
  for (StreamFinding f : m.findings) {
    out.warnings.push_back(Describe(f, m, accel_name, gyro_name));
  }
  if (m.resampled) {
    out.summary = fmt::format(
        "accelerometer {:.1f} Hz ({}), gyroscope {:.1f} Hz ({}): the "
        "gyroscope averaged onto the accelerometer's stamps{}",
        m.accel_rate_hz,
        Count(accel_rows, "row"),
        m.gyro_rate_hz,
        Count(gyro.size(), "sample"),
        m.rows_dropped_before + m.rows_dropped_after == 0
            ? std::string()
            : fmt::format("; {} outside the gyroscope's span dropped",
                          Count(m.rows_dropped_before + m.rows_dropped_after,
                                "accelerometer row")));
  }
  return out;
}

double GravityFlags::Resolve() const {
  if (gravity_mps2) return *gravity_mps2;
  if (latitude_deg) return NormalGravityMps2(*latitude_deg, height_m);
  return kStandardGravityMps2;
}

void AddGravityOptions(CLI::App& app, GravityFlags& flags) {
  auto* g = app.add_option(std::string(FlagName(Option::kGravity)),
                           flags.gravity_mps2,
                           "Local magnitude of gravity (m/s2); default 9.80665, "
                           "the standard value the paper uses")
                ->check(NumberIn(kMinGravityMps2, kMaxGravityMps2))
                ->group("Gravity");
  auto* lat = app.add_option(std::string(FlagName(Option::kLatitude)),
                             flags.latitude_deg,
                             "Geodetic latitude of the site (deg): use the WGS84 "
                             "normal gravity there")
                  ->check(NumberIn(-90.0, 90.0))
                  ->group("Gravity");
  app.add_option(std::string(FlagName(Option::kHeight)),
                 flags.height_m,
                 "Ellipsoidal height of the site (m), with --latitude")
      ->check(FiniteNumber)
      ->needs(lat)
      ->group("Gravity");
  g->excludes(lat);
}

void AddDetectOptions(CLI::App& app, DetectOptions& detect) {
  app.add_option(std::string(FlagName(Option::kDetectWindow)),
                 detect.window_s,
                 "Static detection: moving window of the motion statistic (s)")
      ->capture_default_str()
      ->check(PositiveNumber)
      ->group("Static detection");
  app.add_option(std::string(FlagName(Option::kDetectMinStatic)),
                 detect.min_static_s,
                 "Static detection: shortest still position kept (s)")
      ->capture_default_str()
      ->check(PositiveNumber)
      ->group("Static detection");
  app.add_option(std::string(FlagName(Option::kDetectSettle)),
                 detect.settle_s,
                 "Static detection: trimmed from each end of a position (s)")
      ->capture_default_str()
      ->check(NonNegativeNumber)
      ->group("Static detection");
  app.add_option(std::string(FlagName(Option::kDetectThreshold)),
                 detect.threshold_factor,
                 "Static detection: threshold as a multiple of the quiet level")
      ->capture_default_str()
      ->check(NumberIn(1.0, 100.0))
      ->group("Static detection");
  app.add_option(std::string(FlagName(Option::kDetectMaxStill)),
                 detect.max_still_g,
                 "Static detection: nothing moving more than this (g) is still, whatever "
                 "the quiet level; 0 = no cap")
      ->capture_default_str()
      ->check(NonNegativeNumber)
      ->group("Static detection");
  app.add_option(std::string(FlagName(Option::kDetectMergeGap)),
                 detect.merge_gap_s,
                 "Static detection: merge two positions at the same orientation across a "
                 "bump shorter than this (s)")
      ->capture_default_str()
      ->check(NonNegativeNumber)
      ->group("Static detection");
  app.add_option_function<double>(
         std::string(FlagName(Option::kSensorRange)),
         [&detect](double g) { detect.range_mps2 = g * kStandardGravityMps2; },
         "Static detection: measuring range of the sensor (g, e.g. 2 for ±2 g); "
         "positions "
         "with readings at the limit are dropped with a warning. Default: the limit is "
         "found from runs of identical extreme readings")
      ->check(PositiveNumber)
      ->group("Static detection");
  app.add_option(std::string(FlagName(Option::kDetectMergeAngle)),
                 detect.merge_angle_deg,
                 "Static detection: ... and closer than this in orientation (deg)")
      ->capture_default_str()
      ->check(NumberIn(0.0, 180.0))
      ->group("Static detection");
}

void AddCalibrateOptions(CLI::App& app, CalibrateOptions& options) {
  const std::vector<std::pair<std::string, ModelKind>> models{
      {"shin-el-sheimy-9", ModelKind::kShinElSheimy9},
      {"bias-scale-6", ModelKind::kBiasScale6}};
  const std::vector<std::pair<std::string, RobustLoss>> losses{
      {"none", RobustLoss::kNone},
      {"huber", RobustLoss::kHuber},
      {"cauchy", RobustLoss::kCauchy}};
  app.add_option(
         "--counts-per-g",
         options.counts_per_g,
         "With --units counts: the datasheet's sensitivity (e.g. 16384 for an "
         "MPU-6050 at +-2 g), so that scale-factor errors and biases are relative to "
         "the datasheet, not to the fitted sphere; the calibration file records "
         "which (input.scale_reference)")
      ->check(PositiveNumber)
      ->group("Estimation");
  app.add_option(std::string(FlagName(Option::kModel)),
                 options.solve.model,
                 "Error model: shin-el-sheimy-9 (bias, scale, 3 non-orthogonality "
                 "angles; >= 10 positions) or bias-scale-6 (six-position protocol)")
      ->transform(OneOf(models))
      ->default_str("shin-el-sheimy-9")
      ->group("Estimation");
  app.add_option(std::string(FlagName(Option::kRobust)),
                 options.solve.robust,
                 "Robust loss on the position residuals: none, huber or cauchy")
      ->transform(OneOf(losses))
      ->default_str("none")
      ->group("Estimation");
  AddDetectOptions(app, options.detect);
}

void ThrowIfInvalid(const std::string& problem, const std::string& what) {
  if (!problem.empty()) throw Error(fmt::format("{}: {}", what, problem));
}

}  // namespace mpcal::cli
