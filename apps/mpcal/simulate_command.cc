// mpcal simulate: synthetic sessions with known truth. `simulate static`
// writes a hand-held multi-position session (or N power-ups of one device)
// as a CSV log and its true errors as a calibration file.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "cli_options.h"
#include "command.h"
#include "explain.h"
#include "mpcal/atomic_file.h"
#include "mpcal/calibration_file.h"
#include "mpcal/error.h"
#include "mpcal/log_writer.h"
#include "mpcal/simulate.h"
#include "realtime_output.h"

namespace mpcal::cli {
namespace {

struct SimulateStaticFlags {
  std::string preset = "mti-g";
  std::uint64_t seed = 1;
  std::string output;
  std::string truth;
  int positions = 26;
  double dwell_s = 10.0;
  double turn_s = 2.0;
  double rest_s = 10.0;
  double tilt_deg = 5.0;
  double rate_hz = 0.0;
  std::string units = "mps2";
  double counts_per_mps2 = 400.0;
  double counts_offset = 32768.0;
  std::optional<double> noise_density;
  std::vector<double> turn_on_spread_g;
  std::vector<double> bias_drift_mps2_per_s;
  double shake_accel_mps2 = 1.5;
  double shake_rotation_deg = 3.0;
  bool gyro = false;
  std::string gyro_units = "rads";
  double gyro_counts_per_radps = 4780.0;
  std::optional<double> gyro_noise_density;
  std::optional<double> earth_rate_latitude_deg;
  std::optional<int> trials;
  int digits = 9;
  bool realtime = false;
  std::optional<double> speed;
  GravityFlags gravity;
};

// session.csv -> session_3.csv (trial 3), keeping the directory.
std::string NumberedPath(const std::string& path, int trial) {
  const std::filesystem::path p(path);
  return (p.parent_path() /
          fmt::format("{}_{}{}", p.stem().string(), trial, p.extension().string()))
      .string();
}

SimulateStaticOptions ToOptions(const SimulateStaticFlags& f) {
  SimulateStaticOptions o;
  o.device = FindPreset(f.preset);
  o.seed = f.seed;
  o.positions = f.positions;
  o.dwell_s = f.dwell_s;
  o.turn_s = f.turn_s;
  o.initial_rest_s = f.rest_s;
  o.tilt_deg = f.tilt_deg;
  o.rate_hz = f.rate_hz;
  const std::optional<AccelUnits> units = ParseAccelUnits(f.units);
  if (!units)
    throw Error(
        fmt::format("--units: unknown unit '{}'; use mps2, g or counts", f.units));
  o.units = *units;
  o.counts_per_mps2 = f.counts_per_mps2;
  o.counts_offset = f.counts_offset;
  o.shake_accel_mps2 = f.shake_accel_mps2;
  o.shake_rotation_deg = f.shake_rotation_deg;
  o.gyro = f.gyro;
  o.gyro_units = *ParseGyroUnits(f.gyro_units);
  o.gyro_counts_per_radps = f.gyro_counts_per_radps;
  if (f.gyro_noise_density)
    o.gyro_noise_density_radps_per_sqrt_hz = *f.gyro_noise_density;
  o.earth_rate_latitude_deg = f.earth_rate_latitude_deg;
  if (f.noise_density) o.device.noise_density_mps2_per_sqrt_hz = *f.noise_density;
  if (f.turn_on_spread_g.size() == 1) {
    o.device.turn_on_bias_std_mps2.setConstant(f.turn_on_spread_g[0] *
                                               kStandardGravityMps2);
  } else if (f.turn_on_spread_g.size() == 3) {
    o.device.turn_on_bias_std_mps2 =
        Eigen::Vector3d(
            f.turn_on_spread_g[0], f.turn_on_spread_g[1], f.turn_on_spread_g[2]) *
        kStandardGravityMps2;
  } else if (!f.turn_on_spread_g.empty()) {
    throw Error(fmt::format("--turn-on-spread takes one value or three (x,y,z), got {}",
                            f.turn_on_spread_g.size()));
  }
  if (f.bias_drift_mps2_per_s.size() == 1) {
    o.bias_drift_mps2_per_s.setConstant(f.bias_drift_mps2_per_s[0]);
  } else if (f.bias_drift_mps2_per_s.size() == 3) {
    o.bias_drift_mps2_per_s = Eigen::Vector3d(f.bias_drift_mps2_per_s[0],
                                              f.bias_drift_mps2_per_s[1],
                                              f.bias_drift_mps2_per_s[2]);
  } else if (!f.bias_drift_mps2_per_s.empty()) {
    throw Error(fmt::format("--bias-drift takes one value or three (x,y,z), got {}",
                            f.bias_drift_mps2_per_s.size()));
  }
  ThrowIfInvalid(o.Validate(), "simulate static");
  return o;
}

std::string FormatBiasMg(const Eigen::Vector3d& bias_mps2) {
  const Eigen::Vector3d mg = bias_mps2 / kStandardGravityMps2 * 1e3;
  return fmt::format("{:+.2f}, {:+.2f}, {:+.2f} mg", mg.x(), mg.y(), mg.z());
}

// One session (or trial) to its files.
void WriteSession(const SimulatedSession& session,
                  const std::string& csv_path,
                  const std::string& truth_path,
                  int digits) {
  LogWriteOptions write;
  write.significant_digits = digits;
  WriteRecordingFile(csv_path, session.recording, write);
  if (!truth_path.empty()) {
    Calibration truth = session.truth;
    if (truth.provenance) truth.provenance->mpcal_version = MPCAL_VERSION;
    try {
      WriteCalibrationFile(truth_path, truth);
    } catch (const Error&) {
      // A log without its truth is a partial output: take it back.
      std::error_code ec;
      if (csv_path != "-") std::filesystem::remove(csv_path, ec);
      throw;
    }
  }
}

// At the sensor's pace: the truth first (whole, atomically), then the log
// line by line as the sensor would give it. False when the reader quit.
bool WriteSessionAtPace(const SimulatedSession& session, const SimulateStaticFlags& f) {
  if (!f.truth.empty()) {
    Calibration truth = session.truth;
    if (truth.provenance) truth.provenance->mpcal_version = MPCAL_VERSION;
    WriteCalibrationFile(f.truth, truth);
  }
  LogWriteOptions write;
  write.significant_digits = f.digits;
  std::ostringstream csv;
  WriteRecordingCsv(csv, session.recording, write);
  return WriteAtSensorPace(
      f.output, csv.str(), session.recording.time_s, f.speed.value_or(1.0));
}

// The outputs named sensibly, and writable, before anything is simulated.
void CheckOutputs(const SimulateStaticFlags& f) {
  if (f.output.empty()) throw Error("simulate static: give the output log with -o FILE");
  if ((f.realtime || f.speed) && f.trials) {
    throw Error("simulate static: --realtime writes one session; leave out --trials");
  }
  if (!f.truth.empty() && f.truth == f.output) {
    throw Error(
        fmt::format("simulate static: -o and --truth name the same file '{}'", f.output));
  }
  const bool to_stdout = f.output == "-";
  if (to_stdout && f.trials) {
    throw Error("simulate static: --trials writes numbered files; give -o FILE, not '-'");
  }
  if (f.truth == "-") {
    throw Error(
        "simulate static: --truth needs a file name ('-' is only for the log, -o -)");
  }
  CheckWritable(f.output);
  if (!f.truth.empty()) CheckWritable(f.truth);
}

// One session: its files and the summary.
void RunOne(const SimulateStaticFlags& f,
            const SimulateStaticOptions& options,
            double gravity,
            std::FILE* summary) {
  const bool to_stdout = f.output == "-";
  const std::string_view units = ToString(options.units);
  const SimulatedSession s = SimulateStatic(options, gravity);
  if (f.realtime || f.speed) {
    // The reader quit (a record session that has what it needs): no summary.
    if (!WriteSessionAtPace(s, f)) return;
  } else {
    WriteSession(s, f.output, f.truth, f.digits);
  }
  const double duration = s.recording.size() / s.rate_hz;
  fmt::print(
      summary,
      "Simulated a hand-held {} session (seed {}): {} rows over {:.1f} s at {:g} Hz, "
      "{} position{} held {:g} s each with {:g} s hand turns after {:g} s of rest; "
      "readings in {}{}, white noise σ = {:.4g} m/s² per sample ({:g} m/s²/√Hz){}, "
      "gravity {:.5f} m/s². Wrote {}{}.\n",
      options.device.name,
      f.seed,
      s.recording.size(),
      duration,
      s.rate_hz,
      s.directions.size(),
      s.directions.size() == 1 ? "" : "s",
      options.dwell_s,
      options.turn_s,
      options.initial_rest_s,
      units,
      options.gyro
          ? (options.gyro_units == GyroUnits::kCounts ? " with gyroscope (counts)"
                                                      : " with gyroscope (rad/s)")
          : "",
      s.noise_std_mps2.x(),
      options.device.noise_density_mps2_per_sqrt_hz,
      s.quantisation_step_mps2 > 0
          ? fmt::format(", quantised to {:.4g} m/s²", s.quantisation_step_mps2)
          : std::string(),
      gravity,
      to_stdout ? "the log to standard output" : f.output,
      f.truth.empty() ? " (no --truth: the true errors were not written)"
                      : fmt::format(" and the true errors to {}", f.truth));
  if (!to_stdout) {
    fmt::print(summary,
               "Calibrate it with: mpcal calibrate {} --units {}{}{} -o calib.json\n",
               f.output,
               units,
               f.gravity.gravity_mps2 || f.gravity.latitude_deg
                   ? fmt::format(" --gravity {:.5f}", gravity)
                   : std::string(),
               options.gyro && options.gyro_units == GyroUnits::kCounts
                   ? " --gyro-units counts"
                   : "");
  }
}

// N power-ups of the device: numbered files, a line per trial.
void RunTrials(const SimulateStaticFlags& f,
               const SimulateStaticOptions& options,
               double gravity,
               std::FILE* summary) {
  const std::string_view units = ToString(options.units);
  const int n = *f.trials;
  const std::vector<SimulateStaticOptions> trials = TrialOptions(options, n);
  const Eigen::Vector3d spread_mg =
      options.device.turn_on_bias_std_mps2 / kStandardGravityMps2 * 1e3;
  fmt::print(summary,
             "Simulating {} power-ups of a {} (seed {}): scale-factor errors and "
             "non-orthogonality fixed, bias redrawn each time with a turn-on spread of "
             "{:.2f}, {:.2f}, {:.2f} mg (1σ).\n",
             n,
             options.device.name,
             f.seed,
             spread_mg.x(),
             spread_mg.y(),
             spread_mg.z());
  std::size_t rows = 0;
  double duration = 0.0;
  for (int i = 1; i <= n; ++i) {
    const SimulatedSession s =
        SimulateStatic(trials[static_cast<std::size_t>(i - 1)], gravity);
    const std::string csv = NumberedPath(f.output, i);
    const std::string truth = f.truth.empty() ? std::string() : NumberedPath(f.truth, i);
    WriteSession(s, csv, truth, f.digits);
    fmt::print(summary,
               "  trial {}: {}{}  bias {}\n",
               i,
               csv,
               truth.empty() ? std::string() : ", " + truth,
               FormatBiasMg(s.truth.model.bias_mps2 -
                            (options.units == AccelUnits::kCounts
                                 ? Eigen::Vector3d::Constant(options.counts_offset /
                                                             options.counts_per_mps2)
                                 : Eigen::Vector3d::Zero())));
    rows = s.recording.size();
    duration = rows / s.rate_hz;
    std::fflush(summary);  // a line per trial is the progress report
  }
  fmt::print(summary,
             "Each trial: {} rows over {:.1f} s, {} positions, readings in {}. Wrote {} "
             "through {}{}.\n",
             rows,
             duration,
             options.positions,
             units,
             NumberedPath(f.output, 1),
             NumberedPath(f.output, n),
             f.truth.empty() ? " (no --truth: the true errors were not written)"
                             : fmt::format(" and {} through {}",
                                           NumberedPath(f.truth, 1),
                                           NumberedPath(f.truth, n)));
}

void Run(const SimulateStaticFlags& f) {
  CheckOutputs(f);
  // With the log on stdout the summary must not mix into it.
  std::FILE* summary = f.output == "-" ? stderr : stdout;
  const SimulateStaticOptions options = ToOptions(f);
  const double gravity = f.gravity.Resolve();
  if (f.trials) {
    RunTrials(f, options, gravity, summary);
  } else {
    RunOne(f, options, gravity, summary);
  }
}

void AddOutputOptions(CLI::App* app, SimulateStaticFlags* f) {
  const std::string presets = fmt::format("{}", fmt::join(PresetNames(), ", "));
  app->add_option("--preset", f->preset, "Paper's device (docs/method.md §6): " + presets)
      ->capture_default_str();
  app->add_option("--seed", f->seed, "Random seed; the same seed gives the same session")
      ->capture_default_str();
  app->add_option("-o,--output",
                  f->output,
                  "The log (CSV: t,ax,ay,az[,gx,gy,gz]); '-' for standard output. With "
                  "--trials, FILE_1.csv ... FILE_N.csv")
      ->check(OutputPath)
      ->required();
  app->add_option("--truth",
                  f->truth,
                  "Write the true errors as a calibration file (JSON); with --trials, "
                  "TRUTH_1.json ... TRUTH_N.json")
      ->check(OutputPath);
}

void AddSessionOptions(CLI::App* app, SimulateStaticFlags* f) {
  app->add_option(
         "--positions",
         f->positions,
         "Positions: up to 26 take the cube's faces, edges, corners in that order; "
         "more add random directions")
      ->capture_default_str()
      ->check(CLI::Range(1, 100000))
      ->group("Session");
  app->add_option("--dwell", f->dwell_s, "Still time per position (s)")
      ->capture_default_str()
      ->check(PositiveNumber)
      ->group("Session");
  app->add_option("--turn", f->turn_s, "Duration of each hand turn (s)")
      ->capture_default_str()
      ->check(PositiveNumber)
      ->group("Session");
  app->add_option("--rest", f->rest_s, "Rest at the start (s)")
      ->capture_default_str()
      ->check(NonNegativeNumber)
      ->group("Session");
  app->add_option(
         "--tilt", f->tilt_deg, "Largest random tilt of each cube position (degrees)")
      ->capture_default_str()
      ->check(CLI::Range(0.0, 90.0))
      ->group("Session");
  app->add_option("--shake-accel",
                  f->shake_accel_mps2,
                  "RMS hand acceleration during turns (m/s2)")
      ->capture_default_str()
      ->check(NonNegativeNumber)
      ->group("Session");
  app->add_option("--shake-rotation",
                  f->shake_rotation_deg,
                  "RMS of the small fast rotations during turns (degrees)")
      ->capture_default_str()
      ->check(NonNegativeNumber)
      ->group("Session");
  app->add_option("--trials",
                  f->trials,
                  "Simulate N power-ups of the device: bias redrawn each time, scale and "
                  "non-orthogonality fixed (for 'mpcal repeat')")
      ->check(CLI::Range(1, 1000))
      ->group("Session");
  app->add_option("--turn-on-spread",
                  f->turn_on_spread_g,
                  "1σ of the bias from one power-up to the next (g), one value or x,y,z; "
                  "default: the paper's spread over its three trials")
      ->delimiter(',')
      ->group("Session");
  app->add_option(
         "--bias-drift",
         f->bias_drift_mps2_per_s,
         "A bias drifting linearly over the session (m/s2 per second), one value or "
         "x,y,z, reaching the device's bias at the last sample (a warm-up)")
      ->delimiter(',')
      ->group("Session");
}

void AddAccelerometerOptions(CLI::App* app, SimulateStaticFlags* f) {
  app->add_option(std::string(FlagName(Option::kLogRate)),
                  f->rate_hz,
                  "Sample rate (Hz); default the device's")
      ->check(PositiveNumber)
      ->group("Sensor");
  app->add_option("--noise-density",
                  f->noise_density,
                  "White-noise density (m/s2/√Hz); σ per sample = density·√(rate/2); "
                  "default the device's")
      ->check(NonNegativeNumber)
      ->group("Sensor");
  app->add_option(std::string(FlagName(Option::kLogUnits)),
                  f->units,
                  "Units written: mps2, g (9.80665 m/s2) or counts (integers: "
                  "offset + reading·counts-per-mps2)")
      ->transform(
          OneOf<std::string>({{"mps2", "mps2"}, {"g", "g"}, {"counts", "counts"}}))
      ->capture_default_str()
      ->group("Sensor");
  app->add_option(
         "--counts-per-mps2", f->counts_per_mps2, "ADC sensitivity, with --units counts")
      ->capture_default_str()
      ->check(PositiveNumber)
      ->group("Sensor");
  app->add_option("--counts-offset", f->counts_offset, "ADC zero, with --units counts")
      ->capture_default_str()
      ->group("Sensor");
}

void AddGyroscopeOptions(CLI::App* app, SimulateStaticFlags* f) {
  app->add_flag(
         "--gyro",
         f->gyro,
         "Also write gyroscope columns gx,gy,gz with the device's gyroscope errors "
         "(scale, misalignment, bias with a slow random walk, white noise); the truth "
         "file becomes an IMU file (mpcal.imu/1) with them")
      ->group("Sensor");
  app->add_option(std::string(FlagName(Option::kLogGyroUnits)),
                  f->gyro_units,
                  "Units of the gyroscope columns: rads or counts (integers: 32768 + "
                  "reading·gyro-counts-per-radps)")
      ->transform(OneOf<std::string>({{"rads", "rads"}, {"counts", "counts"}}))
      ->capture_default_str()
      ->group("Sensor");
  app->add_option("--gyro-counts-per-radps",
                  f->gyro_counts_per_radps,
                  "Gyroscope ADC sensitivity, with --gyro-units counts")
      ->capture_default_str()
      ->check(PositiveNumber)
      ->group("Sensor");
  app->add_option("--gyro-noise-density",
                  f->gyro_noise_density,
                  "Gyroscope white-noise density (rad/s/√Hz); default the device's")
      ->check(NonNegativeNumber)
      ->group("Sensor");
  app->add_option("--earth-rate",
                  f->earth_rate_latitude_deg,
                  "Add the Earth's rotation at this latitude (deg) to the gyroscope")
      ->check(CLI::Range(-90.0, 90.0))
      ->group("Sensor");
}

void AddSimulateStaticCommand(CLI::App& simulate) {
  auto f = std::make_shared<SimulateStaticFlags>();
  CLI::App* app = simulate.add_subcommand(
      "static",
      "A hand-held multi-position session with known errors: rest, then each position "
      "held still, with hand turns (rotation and shake) between them");
  AddOutputOptions(app, f.get());
  AddSessionOptions(app, f.get());
  AddAccelerometerOptions(app, f.get());
  AddGyroscopeOptions(app, f.get());
  app->add_option("--digits",
                  f->digits,
                  "Significant digits of the readings in the log (0: exact round trip)")
      ->capture_default_str()
      ->check(CLI::Range(0, 17))
      ->group("Sensor");
  app->add_flag("--realtime",
                f->realtime,
                "Write the log at the pace of the sensor (to standard output or a file "
                "that grows line by line), so that a live session can be tried without "
                "hardware; when the reader quits (a closed pipe), stop quietly with exit "
                "status 0")
      ->group("Output");
  app->add_option("--speed",
                  f->speed,
                  "With --realtime (implied): X times the sensor's pace (20: a 4-minute "
                  "session in 12 s)")
      ->check(PositiveNumber)
      ->group("Output");
  AddGravityOptions(*app, f->gravity);
  app->footer(
      "Examples:\n"
      "  mpcal simulate static --preset mti-g --seed 1 -o session.csv --truth "
      "truth.json\n"
      "  mpcal calibrate session.csv -o calib.json\n"
      "  mpcal simulate static --preset colibri --units g --trials 3 -o s.csv --truth "
      "t.json\n"
      "    (writes s_1.csv s_2.csv s_3.csv and t_1.json t_2.json t_3.json)\n"
      "  mpcal simulate static --preset colibri --gyro -o imu.csv --truth "
      "imu_truth.json\n"
      "  mpcal simulate static --preset mti-g --bias-drift 2e-4 -o warm.csv --truth "
      "warm.json\n"
      "    (a bias warming up by 2e-4 m/s2 per second; calibrate fits the drift)\n"
      "  mpcal simulate static --preset mti-g --realtime --speed 20 -o - | mpcal record "
      "-\n"
      "    (a live session without hardware, 20 times faster than real time)");
  app->callback([f] { Run(*f); });
}

}  // namespace

void AddSimulateCommand(CLI::App& root) {
  CLI::App* simulate = root.add_subcommand(
      "simulate",
      "Write synthetic sessions with known errors (for testing and teaching)");
  simulate->require_subcommand(1);
  simulate->footer(
      "Example:\n"
      "  mpcal simulate static --preset mti-g --seed 1 -o session.csv --truth "
      "truth.json");
  AddSimulateStaticCommand(*simulate);
  // `simulate walk` lives in simulate_walk_command.cc.
  AddSimulateWalkCommand(*simulate);
  // `simulate noise` lives in simulate_noise_command.cc.
  AddSimulateNoiseCommand(*simulate);
}

}  // namespace mpcal::cli
