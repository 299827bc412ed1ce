// Flag groups shared by several subcommands, so that every subcommand spells
// the same option the same way (`--units`, `--columns`, `--gravity`, ...).
#pragma once

#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <CLI/CLI.hpp>

#include "mpcal/calibrate.h"
#include "mpcal/log_reader.h"

namespace mpcal::cli {

/// What `counts` means to a subcommand, in the help of --units and
/// --gyro-units.
struct CountsHelp {
  const char* accel;
  const char* gyro;
};
/// Calibrate's (and the commands that read its sessions'): scales found from
/// the positions and the turns.
inline constexpr CountsHelp kCalibrateCounts{
    "raw ADC; offset and scale found from the positions",
    "raw ADC; zero measured at every position, scale found from the turns"};

/// --columns, --units, --time-unit, --rate, --gyro-units, --topic, --time.
void AddLogOptions(CLI::App& app,
                   LogOptions& options,
                   const CountsHelp& counts = kCalibrateCounts);

/// --gyro-log FILE [--gyro-columns MAP]: the gyroscope in a file of its own,
/// row by row with the main log or at its own rate and stamps. One declaration, one check
/// (an empty name is a usage error; a missing file an input error, as for the main log).
/// --accel-topic TOPIC --gyro-topic TOPIC: the two sensor_msgs/Imu topics
/// of a recording that publishes the sensors apart (the gyroscope's topic
/// may be in the --gyro-log recording).
struct GyroLogFlags {
  std::string path;         ///< empty: not given
  std::string columns;      ///< LogOptions::columns of the gyroscope's log
  std::string accel_topic;  ///< empty: not given
  std::string gyro_topic;   ///< empty: not given
  /// The gyroscope is a stream of its own (a file or a topic).
  bool given() const { return !path.empty() || !gyro_topic.empty(); }
};
/// Declares the flags; call after AddLogOptions (--accel-topic excludes
/// --topic).
void AddGyroLogOptions(CLI::App& app, GyroLogFlags& flags);
/// The main log's options with --accel-topic as its topic.
LogOptions WithAccelTopic(LogOptions log, const GyroLogFlags& flags);
/// With --gyro-log or --gyro-topic: reads the gyroscope's stream (ReadGyroLog:
/// the main log's time unit, rate and gyroscope units, its own columns or
/// topic; a --gyro-topic without --gyro-log is read from `input`) and merges
/// it into `recording` (MergeGyroLog), whose own angular velocity is then
/// not used.
struct MergedStreams {
  /// The gyroscope log's warnings, then one per finding of the merge.
  std::vector<std::string> warnings;
  /// The two streams' rates and how they were joined; empty when they were
  /// taken row by row (or there is no gyroscope stream).
  std::string summary;
};
MergedStreams MergeGyroLogFile(Recording& recording,
                               const std::string& input,
                               const GyroLogFlags& flags,
                               const LogOptions& log);

/// --gravity | --latitude [--height]: the local magnitude of gravity.
struct GravityFlags {
  std::optional<double> gravity_mps2;
  std::optional<double> latitude_deg;
  double height_m = 0.0;
  /// The value to use: the given one, WGS84 normal gravity at the site, or
  /// standard gravity (9.80665 m/s², the paper's) by default.
  double Resolve() const;
};
void AddGravityOptions(CLI::App& app, GravityFlags& flags);

/// Static detection's tuning (--window, --min-static, ...): every command
/// that finds still positions.
void AddDetectOptions(CLI::App& app, DetectOptions& options);

/// Estimation (--counts-per-g, --model, --robust) and detection
/// (AddDetectOptions): the commands that calibrate.
void AddCalibrateOptions(CLI::App& app, CalibrateOptions& options);

/// Checks for numeric flags: a finite number > 0 (>= 0). CLI11's own
/// PositiveNumber / NonNegativeNumber print their range up to DBL_MAX, digit
/// by digit, in the error; these say what is wrong ("--rate: must be a
/// positive number, got -1").
extern const CLI::Validator PositiveNumber;
extern const CLI::Validator NonNegativeNumber;
/// A number in [lo, hi]. CLI::Range lets NaN through (every comparison with
/// it is false), and the value then fails later as an error of the run
/// rather than of the flag; this check refuses it ("--confidence: must be a
/// number in [0.5, 0.999], got 'nan'").
CLI::Validator NumberIn(double lo, double hi);
/// Any finite number (not nan, not inf).
extern const CLI::Validator FiniteNumber;

/// Check for an output file name: not empty (`-o ''` is a slip, not a
/// request to write nothing).
extern const CLI::Validator OutputPath;
/// Check for an output directory name: not empty (the current directory is
/// '.').
extern const CLI::Validator OutputDirectory;
/// Check for an input file name: not empty (`''` is a slip: a shell variable
/// that was never set, not a request to read nothing).
extern const CLI::Validator InputPath;

/// A transform from names (any case) to values: an enum, or the name itself
/// for a string option. An unknown name gets "'tukey' is not one of: none,
/// huber, cauchy"; CLI11's own CheckedTransformer prints its internal
/// mapping of names to numbers instead.
template <typename Value>
CLI::Validator OneOf(std::vector<std::pair<std::string, Value>> choices) {
  std::string names;
  for (const auto& choice : choices) names += (names.empty() ? "" : ", ") + choice.first;
  return CLI::Validator(
      [choices, names](std::string& text) -> std::string {
        const std::string key = CLI::detail::to_lower(text);
        for (const auto& [name, value] : choices) {
          if (name != key) continue;
          if constexpr (std::is_enum_v<Value>) {
            text = std::to_string(static_cast<std::underlying_type_t<Value>>(value));
          } else {
            text = value;
          }
          return "";
        }
        return fmt::format("'{}' is not one of: {}", text, names);
      },
      "{" + names + "}");
}

/// Throws mpcal::Error naming the option when `problem` is not empty.
void ThrowIfInvalid(const std::string& problem, const std::string& what);

}  // namespace mpcal::cli
