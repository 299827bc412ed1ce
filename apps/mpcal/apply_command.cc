// `mpcal apply CALIB.json INPUT -o OUTPUT`: corrects every accelerometer row
// of a log with a calibration file, keeping everything else as it is.
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "calibration_table.h"
#include "cli_options.h"
#include "command.h"
#include "explain.h"
#include "explain_apply.h"
#include "mpcal/apply.h"
#include "mpcal/atomic_file.h"
#include "mpcal/bag.h"
#include "mpcal/calibration_file.h"
#include "mpcal/count.h"
#include "mpcal/error.h"
#include "mpcal/noise_file.h"
#include "progress.h"

namespace mpcal::cli {
namespace {

struct ApplyFlags {
  std::string calibration;
  std::string input;
  std::string output;
  ApplyOptions options;
  std::optional<AccelUnits> out_units;
  std::optional<GyroUnits> out_gyro_units;
  std::string noise;
};

// A file whose gyroscope block says rad/s while the command line it records
// read the log in deg/s holds M and b in rad/s for logs in deg/s: read as
// its block says, such a log would be corrected 57.3 times too large.
// (A calibration made from a log in deg/s records 'dps' in its block.)
void RefuseUnitsLostInProvenance(const std::string& path, const Calibration& c) {
  if (!c.gyroscope || c.gyroscope->input_units != GyroUnits::kRadps || !c.provenance) {
    return;
  }
  const std::string flag =
      fmt::format("{} {}", FlagName(Option::kLogGyroUnits), ToString(GyroUnits::kDps));
  const std::string& recorded = c.provenance->options;
  const auto at = recorded.find(flag);
  if (at == std::string::npos ||
      (at + flag.size() < recorded.size() && recorded[at + flag.size()] != ' ')) {
    return;
  }
  throw Error(ErrorKind::kUnits,
              fmt::format("'{}': the gyroscope block is for logs in rad/s, but the file "
                          "was calibrated from a log in deg/s ('{}' in its provenance); "
                          "calibrate again, or give {} with the units of the log to "
                          "correct",
                          path,
                          flag,
                          FlagName(Option::kLogGyroUnits)));
}

// The options from the flags; what the user left out comes from the
// calibration: a log from the calibrated sensor is in the calibration's units
// and read as the log it was made from (columns, time unit, rate), so that no
// flags need repeating for logs of the same logger.
ApplyOptions OptionsFor(const CLI::App& cmd,
                        const ApplyFlags& flags,
                        const Calibration& calibration) {
  ApplyOptions options = flags.options;
  if (cmd.count(std::string(FlagName(Option::kLogUnits))) == 0) {
    options.log.units = calibration.input_units;
  }
  if (calibration.input_layout &&
      cmd.count(std::string(FlagName(Option::kLogColumns))) == 0 &&
      cmd.count(std::string(FlagName(Option::kLogTimeUnit))) == 0 &&
      cmd.count(std::string(FlagName(Option::kLogRate))) == 0) {
    const Calibration::InputLayout& layout = *calibration.input_layout;
    options.log.columns = layout.columns;
    if (const auto unit = ParseTimeUnit(layout.time_unit)) options.log.time_unit = *unit;
    options.log.rate_hz = layout.rate_hz;
  }
  options.out_units = flags.out_units;
  options.out_gyro_units = flags.out_gyro_units;
  // Likewise the gyroscope columns: in the calibration's units unless told.
  // A --gyro-units given wins, as --units does: it describes the log being
  // corrected, and rad/s and deg/s convert exactly (counts and physical
  // units do not: GyroCorrector refuses the mix).
  if (calibration.gyroscope &&
      cmd.count(std::string(FlagName(Option::kLogGyroUnits))) == 0) {
    RefuseUnitsLostInProvenance(flags.calibration, calibration);
    options.log.gyro_in_counts = calibration.gyroscope->input_units == GyroUnits::kCounts;
    options.log.gyro_in_dps = calibration.gyroscope->input_units == GyroUnits::kDps;
  }
  return options;
}

// ApplyCalibration, and once more without the recorded layout when the
// recorded columns do not fit the log (a log of another logger: read it as
// any log, by the header's names or t,ax,ay,az).
ApplyResult ApplyWithFallback(const CLI::App& cmd,
                              const ApplyFlags& flags,
                              const Calibration& calibration,
                              const ApplyOptions& options) {
  try {
    return ApplyCalibration(calibration, flags.input, flags.output, options);
  } catch (const Error& e) {
    if (!calibration.input_layout || options.log.columns.empty() ||
        e.kind() != ErrorKind::kColumns ||
        cmd.count(std::string(FlagName(Option::kLogColumns))) > 0) {
      throw;
    }
  }
  ApplyOptions plain = options;
  plain.log.columns = flags.options.log.columns;
  plain.log.time_unit = flags.options.log.time_unit;
  plain.log.rate_hz = flags.options.log.rate_hz;
  return ApplyCalibration(calibration, flags.input, flags.output, plain);
}

void PrintSummary(const ApplyFlags& flags,
                  const Calibration& calibration,
                  const ApplyResult& result) {
  fmt::print("corrected {} of '{}' into '{}' (accelerometer in {}",
             Count(result.data_rows, "row"),
             flags.input,
             flags.output,
             ToString(result.out_units));
  if (result.gyro_corrected) {
    auto name = [](GyroUnits u) {
      return u == GyroUnits::kDps ? "deg/s" : u == GyroUnits::kRadps ? "rad/s" : "counts";
    };
    if (result.log_gyro_units == result.out_gyro_units) {
      fmt::print(", gyroscope in {}", name(result.out_gyro_units));
    } else {
      fmt::print(", gyroscope from {} to {}",
                 name(result.log_gyro_units),
                 name(result.out_gyro_units));
    }
  }
  if (result.rest_magnitude_mps2) {
    fmt::print("; |a| at rest {:.5f} m/s², gravity {:.5f} m/s²",
               *result.rest_magnitude_mps2,
               calibration.gravity_mps2);
  }
  fmt::print(")\n");
}

// The extension a recording of `format` is written under.
std::string_view ExtensionOf(BagFormat format) {
  return format == BagFormat::kRos1 ? ".bag" : format == BagFormat::kMcap ? ".mcap" : "";
}

// The white noise density of each axis of a noise analysis's sensor; empty
// when an axis has none measured.
std::optional<Eigen::Vector3d> WhiteNoiseOf(const SensorNoise& sensor) {
  Eigen::Vector3d n;
  for (int i = 0; i < 3; ++i) {
    const auto& value =
        sensor.axes[static_cast<std::size_t>(i)].term(NoiseTerm::kWhiteNoise).value;
    if (!value) return std::nullopt;
    n[i] = *value;
  }
  return n;
}

void SetWhiteNoise(const std::string& path, BagApplyOptions& options) {
  const NoiseFile noise = ReadNoiseFile(path);
  options.accel_white_noise_mps2_per_rthz = WhiteNoiseOf(noise.result.accel_mps2);
  if (!options.accel_white_noise_mps2_per_rthz) {
    throw Error(ErrorKind::kInput,
                fmt::format("'{}': the accelerometer's white noise is not measured on "
                            "every axis, so the covariances cannot be set from it",
                            path));
  }
  if (noise.result.gyro_radps) {
    options.gyro_white_noise_radps_per_rthz = WhiteNoiseOf(*noise.result.gyro_radps);
  }
}

// The one line that says whose covariances the messages carry.
void PrintCovariances(const ApplyFlags& flags, const BagApplyResult& result) {
  if (!result.covariance_rate_hz) {
    fmt::print(stderr,
               "mpcal: the covariances are the input's, copied as they are (the "
               "calibration removes systematic errors, not the noise the driver "
               "states)\n");
    return;
  }
  const auto diagonal = [](const Eigen::Vector3d& v) {
    return fmt::format("{:.4g}, {:.4g}, {:.4g}", v.x(), v.y(), v.z());
  };
  fmt::print(stderr,
             "mpcal: the covariances are set from '{}' as N²·f at {:.6g} Hz: linear "
             "acceleration diagonal {} (m/s²)²{}\n",
             flags.noise,
             *result.covariance_rate_hz,
             diagonal(*result.covariances.linear_acceleration_m2ps4),
             result.covariances.angular_velocity_rad2ps2
                 ? fmt::format(", angular velocity diagonal {} (rad/s)²",
                               diagonal(*result.covariances.angular_velocity_rad2ps2))
                 : std::string("; the angular velocity's are the input's (the file has "
                               "no gyroscope white noise)"));
}

// A recording corrected into a recording of its own kind. Its messages are
// in m/s² and rad/s in and out, so the flags that say how a text log is
// read or written have nothing to act on.
void RunApplyBag(const CLI::App& cmd, const ApplyFlags& flags) {
  for (const std::string& name : {std::string(FlagName(Option::kLogColumns)),
                                  std::string(FlagName(Option::kLogUnits)),
                                  std::string(FlagName(Option::kLogGyroUnits)),
                                  std::string(FlagName(Option::kLogTimeUnit)),
                                  std::string(FlagName(Option::kLogRate)),
                                  std::string("--out-units"),
                                  std::string("--out-gyro-units")}) {
    if (cmd.count(name) > 0) {
      throw CLI::ValidationError(
          name,
          fmt::format(
              "'{}' is a recording, read and written in m/s² and rad/s; {} is for "
              "text logs",
              flags.input,
              name));
    }
  }
  const BagFormat format = DetectBagFormat(flags.input);
  const std::string_view extension = ExtensionOf(format);
  if (extension.empty()) {
    throw Error(ErrorKind::kInput,
                fmt::format("'{}' is a ROS 2 bag, which is read but not written; apply "
                            "the calibration to a ROS 1 bag or an MCAP file",
                            flags.input));
  }
  if (!flags.output.ends_with(extension)) {
    throw CLI::ValidationError(
        "--output",
        fmt::format("'{}' is {} and is corrected into one: name the output '*{}'",
                    flags.input,
                    format == BagFormat::kRos1 ? "a ROS 1 bag" : "an MCAP file",
                    extension));
  }
  CheckOutput(flags.output, {flags.calibration, flags.input, flags.noise});
  const Calibration calibration = ReadCalibrationFile(flags.calibration);
  BagApplyOptions options;
  options.topic = flags.options.log.topic;
  if (!flags.noise.empty()) SetWhiteNoise(flags.noise, options);
  const BagApplyResult result =
      ApplyCalibrationToBag(calibration, flags.input, flags.output, options);
  PrintWarnings(result.warnings);
  if (result.unmeasured_messages > 0) {
    PrintWarnings({fmt::format(
        "{} on '{}' mark the linear acceleration as not measured and are copied as they "
        "are",
        Count(static_cast<std::size_t>(result.unmeasured_messages), "message"),
        result.topic)});
  }
  // A recording states its units (m/s², REP 103): no flag would change them.
  if (result.rest_mismatch) {
    PrintWarnings({result.rest_mismatch->what +
                   "; is it the calibrated sensor, and does its driver publish m/s²?"});
  }
  PrintCovariances(flags, result);
  fmt::print(
      "corrected {} on '{}' of '{}' into '{}' (linear acceleration{}; {} of other "
      "topics copied; chunks {}",
      Count(static_cast<std::size_t>(result.corrected_messages), "message"),
      result.topic,
      flags.input,
      flags.output,
      result.gyro_corrected ? " and angular velocity" : "",
      Count(static_cast<std::size_t>(result.other_messages), "message"),
      result.compressions.empty()
          ? std::string("none")
          : fmt::format("{}", fmt::join(result.compressions, ", ")));
  if (result.rest_magnitude_mps2) {
    fmt::print("; |a| at rest {:.5f} m/s², gravity {:.5f} m/s²",
               *result.rest_magnitude_mps2,
               calibration.gravity_mps2);
  }
  fmt::print(")\n");
}

void RunApply(const CLI::App& cmd, const ApplyFlags& flags) {
  if (IsBag(flags.input)) return RunApplyBag(cmd, flags);
  if (!flags.noise.empty()) {
    throw CLI::ValidationError(
        "--noise",
        fmt::format("'{}' is a text log, which has no covariances: the noise analysis "
                    "sets those of a ROS 1 bag or an MCAP file",
                    flags.input));
  }
  if (flags.calibration == "-" && flags.input == "-") {
    throw Error("the calibration file and the log cannot both be standard input ('-')");
  }
  // The log is refused as the output inside ApplyCalibration; the
  // calibration file is only known here.
  CheckOutput(flags.output, {flags.calibration});
  const Calibration calibration = ReadCalibrationFile(flags.calibration);
  ApplyOptions options = OptionsFor(cmd, flags, calibration);
  TerminalProgress progress("applying " + flags.calibration + " to " + flags.input);
  options.log.progress = progress.Callback();
  const ApplyResult result = ApplyWithFallback(cmd, flags, calibration, options);
  progress.Done();
  PrintWarnings(result.warnings);
  if (result.rest_mismatch) PrintWarnings({ExplainRestMismatch(*result.rest_mismatch)});
  // The flag wins over the file; a flag that differs from it is said, in
  // case it was a slip.
  if (result.gyro_corrected &&
      result.log_gyro_units != calibration.gyroscope->input_units) {
    PrintWarnings({fmt::format(
        "the log's gyroscope was read in {} as {} says; the gyroscope of '{}' is for "
        "logs in {}",
        ToString(result.log_gyro_units),
        FlagName(Option::kLogGyroUnits),
        flags.calibration,
        ToString(calibration.gyroscope->input_units))});
  }
  // Standard output may be the corrected log itself: the summary goes there
  // only when the log went to a file.
  if (flags.output != "-") {
    PrintSummary(flags, calibration, result);
    if (calibration.imported_from) {
      fmt::print("calibration imported from {}: no 1σ\n", *calibration.imported_from);
    }
  }
}

}  // namespace

void AddApplyCommand(CLI::App& root) {
  auto flags = std::make_shared<ApplyFlags>();
  CLI::App* cmd = root.add_subcommand("apply",
                                      "Correct a log with a calibration file: every "
                                      "accelerometer row by eqs 8-10, and the "
                                      "gyroscope columns by ω = M (raw − b) with an IMU "
                                      "calibration; the other columns, the "
                                      "header, comments and row order kept as they are.");
  cmd->add_option("CALIB",
                  flags->calibration,
                  "Calibration file (JSON) written by 'mpcal calibrate'")
      ->check(InputPath)
      ->required();
  cmd->add_option("INPUT", flags->input, "Log to correct ('-': standard input)")
      ->check(InputPath)
      ->required();
  cmd->add_option("-o,--output",
                  flags->output,
                  "Corrected log ('-': standard output); written whole or not at all")
      ->check(OutputPath)
      ->required();
  AddLogOptions(*cmd, flags->options.log);
  const std::vector<std::pair<std::string, AccelUnits>> out_units{
      {"mps2", AccelUnits::kMps2}, {"g", AccelUnits::kG}};
  cmd->add_option("--out-units",
                  flags->out_units,
                  "Units of the corrected accelerometer columns: mps2 or g (default: the "
                  "log's units; m/s2 for a log in counts)")
      ->transform(OneOf(out_units))
      ->group("Output");
  const std::vector<std::pair<std::string, GyroUnits>> out_gyro_units{
      {"rads", GyroUnits::kRadps}, {"dps", GyroUnits::kDps}};
  cmd->add_option(
         "--out-gyro-units",
         flags->out_gyro_units,
         "Units of the corrected gyroscope columns (an IMU calibration): rads or dps "
         "(default: the log's units; rad/s for a log in counts)")
      ->transform(OneOf(out_gyro_units))
      ->group("Output");
  cmd->add_option("--noise",
                  flags->noise,
                  "Noise analysis (JSON of 'mpcal noise --json'): the covariances of a "
                  "corrected recording's vectors set to N²·f per axis (f the topic's "
                  "message rate); default: the recording's own kept")
      ->check(InputPath)
      ->group("Output");
  cmd->footer(
      "Example:\n"
      "  mpcal apply calib.json session.csv -o corrected.csv\n"
      "  logger | mpcal apply calib.json - -o - --out-units g | plot\n"
      "  mpcal apply imu.json imu_session.csv -o corrected.csv --out-gyro-units dps\n"
      "  mpcal apply imu.json drive.bag -o drive_corrected.bag --topic /imu/data\n"
      "The log is read with the calibration's units unless --units is given (and its\n"
      "gyroscope in the calibration's units unless --gyro-units is given), and with "
      "the\n"
      "columns, time unit and rate the calibration was made with unless --columns,\n"
      "--time-unit or --rate is given; a log whose magnitude at rest is far from the\n"
      "calibration's gravity gets a warning. With --out-units g, unit labels in the\n"
      "header's accelerometer names follow ('(m/s^2)' becomes '(g)').\n"
      "A ROS 1 bag or an MCAP file is corrected into a recording of its kind (the\n"
      "output named *.bag or *.mcap): the sensor_msgs/Imu messages of the topic\n"
      "corrected, their covariances and every other topic copied as they are.");
  cmd->callback([cmd, flags] { RunApply(*cmd, *flags); });
}

}  // namespace mpcal::cli
