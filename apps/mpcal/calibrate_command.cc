// mpcal calibrate: a raw log in, a calibration file and a table out.
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "calibrate_run.h"
#include "calibration_table.h"
#include "cli_options.h"
#include "command.h"
#include "explain_checks.h"
#include "explain_detect.h"
#include "gyro_table.h"
#include "mpcal/atomic_file.h"
#include "mpcal/bag.h"
#include "mpcal/calibrate.h"
#include "mpcal/calibration_file.h"
#include "mpcal/count.h"
#include "mpcal/error.h"
#include "mpcal/gyro_log.h"
#include "mpcal/log_reader.h"
#include "mpcal/verdict.h"
#include "progress.h"

namespace mpcal::cli {
namespace {

// The options that shaped the result, as a command line a user can rerun.
std::string DescribeOptions(const CalibrateFlags& f) {
  return fmt::format(
             "--units {} --gravity {:.6f} --model {} --robust {} --window {} "
             "--min-static {} "
             "--settle {} --threshold {}{}",
             ToString(f.log.units),
             f.calibrate.solve.gravity_mps2,
             ToString(f.calibrate.solve.model),
             ToString(f.calibrate.solve.robust),
             f.calibrate.detect.window_s,
             f.calibrate.detect.min_static_s,
             f.calibrate.detect.settle_s,
             f.calibrate.detect.threshold_factor,
             f.log.columns.empty() ? "" : " --columns " + f.log.columns) +
         (f.gyro_log.path.empty() ? "" : " --gyro-log " + f.gyro_log.path) +
         (f.gyro_log.columns.empty() ? "" : " --gyro-columns " + f.gyro_log.columns) +
         (f.gyro_log.accel_topic.empty() ? ""
                                         : " --accel-topic " + f.gyro_log.accel_topic) +
         (f.gyro_log.gyro_topic.empty() ? "" : " --gyro-topic " + f.gyro_log.gyro_topic) +
         fmt::format(" --gyro-units {} --gyro-g-sensitivity {}",
                     ToString(f.log.gyro_units()),
                     ToString(f.calibrate.gyro.g_sensitivity));
}

// How the log was read, for the calibration file, so that 'mpcal apply'
// reads logs of the same logger alike without the flags repeated. Found
// again from the log's first lines (a regular file only: standard input and
// pipes cannot be read twice). A robotics recording has no columns to record.
std::optional<Calibration::InputLayout> RecordedLayout(const std::string& input,
                                                       const LogOptions& options) {
  std::error_code ec;
  if (input == "-" || !std::filesystem::is_regular_file(input, ec) || IsBag(input)) {
    return std::nullopt;
  }
  LogOptions quiet = options;
  quiet.progress = nullptr;
  const LogScanner scanner(input, quiet);
  const LogLayout& layout = scanner.layout();
  auto name = [&](int column) {
    const std::string& n = layout.column_names[static_cast<std::size_t>(column)];
    const bool usable = layout.header_line > 0 && !n.empty() &&
                        n.find_first_of(",=") == std::string::npos;
    return usable ? n : std::to_string(column);
  };
  std::string columns;
  if (layout.time_column >= 0) columns = "t=" + name(layout.time_column);
  static constexpr const char* kKeys[] = {"ax", "ay", "az"};
  for (int i = 0; i < 3; ++i) {
    columns += fmt::format("{}{}={}",
                           columns.empty() ? "" : ",",
                           kKeys[i],
                           name(layout.accel_columns[static_cast<std::size_t>(i)]));
  }
  if (layout.has_gyro()) {
    static constexpr const char* kGyroKeys[] = {"gx", "gy", "gz"};
    for (int i = 0; i < 3; ++i) {
      columns += fmt::format(
          ",{}={}", kGyroKeys[i], name(layout.gyro_columns[static_cast<std::size_t>(i)]));
    }
  }
  Calibration::InputLayout out;
  out.columns = columns;
  out.time_unit = std::string(ToString(layout.time_unit));
  if (layout.time_unit == TimeUnit::kSampleIndex) out.rate_hz = options.rate_hz;
  return out;
}

}  // namespace

void RunCalibrate(CalibrateFlags& f) {
  if (!f.output.empty()) CheckOutput(f.output, {f.input, f.gyro_log.path});
  f.calibrate.solve.gravity_mps2 = f.gravity.Resolve();
  ThrowIfInvalid(f.calibrate.Validate(), "calibrate");

  // Found before the rows are read: its scanner's mebibyte buffer is then
  // free again by the time the rows and the fit take the most memory.
  std::optional<Calibration::InputLayout> input_layout = RecordedLayout(f.input, f.log);
  TerminalProgress progress("reading " + f.input);
  f.log.progress = progress.Callback();
  Recording recording = ReadLog(f.input, WithAccelTopic(f.log, f.gyro_log));
  progress.Done();
  PrintWarnings(recording.warnings);
  const MergedStreams streams = MergeGyroLogFile(recording, f.input, f.gyro_log, f.log);
  PrintWarnings(streams.warnings);

  if (f.calibrate.counts_per_g > 0.0 && f.log.units != AccelUnits::kCounts) {
    throw Error("--counts-per-g is the scale of raw counts: it goes with --units counts");
  }
  CalibrateResult result =
      WithDetectWords([&] { return CalibrateRecording(recording, f.calibrate); });
  // The detection's notes lead the warnings: in the command line's words.
  const auto& notes = result.detection.notes;
  for (std::size_t k = 0; k < notes.size() && k < result.warnings.size(); ++k) {
    result.warnings[k] = ExplainNote(notes[k]);
    if (k < result.calibration.warnings.size()) {
      result.calibration.warnings[k] = result.warnings[k];
    }
  }
  result.calibration.provenance = Provenance{MPCAL_VERSION, f.input, DescribeOptions(f)};
  result.calibration.input_layout = std::move(input_layout);

  fmt::print("{}: {}, {:.1f} s; model {}, gravity {:.5f} m/s2\n",
             f.input,
             Count(recording.size(), "row"),
             recording.time_s.back() - recording.time_s.front(),
             ToString(f.calibrate.solve.model),
             f.calibrate.solve.gravity_mps2);
  if (!streams.summary.empty()) fmt::print("{}\n", streams.summary);
  fmt::print("{}", FormatParameterTable(result.calibration, {}, f.verbose));
  if (f.verbose) fmt::print("\n{}", FormatFitSummary(result));
  if (result.gyro) {
    if (result.calibration.gyroscope) {
      fmt::print("\n{}",
                 FormatGyroTable(*result.calibration.gyroscope, nullptr, "", f.verbose));
    }
    if (f.verbose) fmt::print("{}", FormatGyroSummary(*result.gyro));
  }
  fmt::print("\n{}", FormatChecks(JudgeCalibration(result, f.calibrate), stdout));
  PrintWarnings(result.warnings);
  if (result.gyro) {
    // The file says what the command says: a gyroscope that is not
    // calibrated has no block in it (CalibrateRecording), and why is among
    // its warnings.
    const std::vector<std::string> gyro_lines = GyroFindingMessages(*result.gyro);
    PrintWarnings(gyro_lines);
    std::vector<std::string>& kept = result.calibration.warnings;
    kept.insert(kept.end(), gyro_lines.begin(), gyro_lines.end());
  }
  if (!result.solve.converged()) {
    throw Error(
        fmt::format("{}: the fit did not converge ({}); no calibration written. "
                    "Check the positions with 'mpcal detect {}'",
                    f.input,
                    result.solve.message,
                    f.input));
  }
  if (!f.output.empty()) {
    WriteCalibrationFile(f.output, result.calibration);
    fmt::print("wrote {}\n", f.output);
  }
}

void AddCalibrateCommand(CLI::App& root) {
  auto flags = std::make_shared<CalibrateFlags>();
  CLI::App* app = root.add_subcommand(
      "calibrate",
      "Detect the static positions in a log, estimate bias, scale-factor errors and "
      "non-orthogonality with their 1σ, and the gyroscope (M and bias) from the turns "
      "between the positions when the log has one; write a calibration file");
  app->add_option("INPUT", flags->input, "Log: CSV or text, '-' for standard input")
      ->check(InputPath)
      ->required();
  app->add_option("-o,--output",
                  flags->output,
                  "Calibration file to write (JSON: mpcal.imu/1 with the gyroscope, "
                  "mpcal.accelerometer/1 without); without it, only print")
      ->check(OutputPath);
  AddLogOptions(*app, flags->log);
  AddGyroLogOptions(*app, flags->gyro_log);
  app->add_option(
         "--gyro-window",
         flags->calibrate.gyro.direction_window_s,
         "Gravity direction at each end of a turn: the accelerometer's mean over this "
         "long (s) next to the turn; 0 = the whole position")
      ->capture_default_str()
      ->check(NonNegativeNumber)
      ->group("Gyroscope");
  const std::vector<std::pair<std::string, GSensitivity>> g_modes{
      {"auto", GSensitivity::kAuto},
      {"on", GSensitivity::kOn},
      {"off", GSensitivity::kOff}};
  app->add_option(
         "--gyro-g-sensitivity",
         flags->calibrate.gyro.g_sensitivity,
         "Model the gyroscope bias's sensitivity to specific force (b = b0 + G f) "
         "from the positions: auto (when the biases show it), on or off")
      ->transform(OneOf(g_modes))
      ->default_str("auto")
      ->group("Gyroscope");
  AddGravityOptions(*app, flags->gravity);
  AddCalibrateOptions(*app, flags->calibrate);
  app->add_flag("-v,--verbose",
                flags->verbose,
                "Also print the diagnostics behind each check: the fit's residuals and "
                "variance factor, the white noise, the drift test's p, the split-half z "
                "per parameter, the nominal scale of counts, the gyroscope's turns");
  app->footer(
      "Examples:\n"
      "  mpcal calibrate session.csv -o calib.json\n"
      "  mpcal calibrate xsens_acc.mat --units counts --gravity 9.81744 -o xsens.json\n"
      "  mpcal calibrate imu.csv --gyro-units dps -o imu.json   (columns ax..az, "
      "gx..gz)\n"
      "  mpcal calibrate xsens_acc.mat --gyro-log xsens_gyro.mat --units counts \\\n"
      "      --gyro-units counts --gravity 9.81744 -o xsens_imu.json\n"
      "  mpcal calibrate TotalAcceleration.csv --gyro-log Gyroscope.csv -o phone.json\n"
      "  mpcal calibrate d435i.bag --accel-topic /camera/accel/sample \\\n"
      "      --gyro-topic /camera/gyro/sample -o d435i.json\n"
      "  mpcal calibrate six_poses.csv --model bias-scale-6 --latitude 49.6 --height "
      "300\n"
      "  mpcal calibrate arduino_serial.txt --units counts --counts-per-g 16384 -o "
      "mpu6050.json\n\n"
      "The table is followed by one line per check: good, look at (usable, but read "
      "why) or do not use. Verdicts and warnings are coloured on a terminal; set "
      "NO_COLOR=1 for plain text.");
  app->callback([flags] { RunCalibrate(*flags); });
}

}  // namespace mpcal::cli
