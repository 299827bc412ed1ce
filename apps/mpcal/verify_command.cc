// `mpcal verify --imu WALK --gnss REF [--calib CALIB.json] -o RESULT.json`:
// the paper's field verification (docs/method.md §5): integrate a walk raw and
// corrected and compare both with a GNSS reference.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "calibration_table.h"
#include "cli_options.h"
#include "command.h"
#include "explain.h"
#include "explain_checks.h"
#include "explain_detect.h"
#include "explain_verify.h"
#include "mpcal/atomic_file.h"
#include "mpcal/calibrate.h"
#include "mpcal/calibration_file.h"
#include "mpcal/count.h"
#include "mpcal/error.h"
#include "mpcal/gnss.h"
#include "mpcal/gravity.h"
#include "mpcal/log_reader.h"
#include "mpcal/verification_file.h"
#include "mpcal/verify.h"
#include "progress.h"

namespace mpcal::cli {
namespace {

// `path` as the result file at `result` should name it: relative to the
// result's folder (absolute when the result goes to standard output).
std::string RelativeTo(const std::string& path, const std::string& result) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path absolute = fs::absolute(path, ec);
  if (result == "-" || ec) return absolute.string();
  const fs::path folder = fs::absolute(result, ec).parent_path();
  const fs::path relative = fs::proximate(absolute, folder, ec);
  return ec ? absolute.string() : relative.string();
}

struct VerifyFlags {
  std::string imu;
  std::string gnss;
  std::string calibration;
  std::string output;
  std::string trajectory_prefix;
  LogOptions log;
  GnssReadOptions gnss_options;
  GravityFlags gravity;
  VerifyOptions options;
  std::optional<double> time_offset_s;
  bool no_gyro = false;
  bool no_zupt = false;
  bool verbose = false;
};

void PrintRow(std::FILE* out, const char* name, const PathMetrics& m) {
  fmt::print(out,
             "  {:<10} {:>12.2f} {:>12.2f} {:>12.2f} {:>12.1f}\n",
             name,
             m.start_end_distance_m,
             m.horizontal_rms_m,
             m.horizontal_max_m,
             m.path_length_m);
}

std::string TrajectoryPath(const std::string& prefix, const std::string& role) {
  return prefix + "-" + role + ".csv";
}

struct VerifyInputs {
  std::optional<Calibration> calibration;
  Recording imu;
  GnssTrack reference;
};

VerifyInputs ReadInputs(const CLI::App& cmd, VerifyFlags& f) {
  VerifyInputs in;
  if (!f.calibration.empty()) {
    in.calibration = ReadCalibrationFile(f.calibration);
    // A log of the calibrated sensor is in the calibration's units unless
    // the user says otherwise.
    if (cmd.count(std::string(FlagName(Option::kLogUnits))) == 0) {
      f.log.units = in.calibration->input_units;
    }
  }
  ThrowIfInvalid(f.log.Validate(), "log options");
  TerminalProgress progress("reading " + f.imu);
  f.log.progress = progress.Callback();
  in.imu = ReadLog(f.imu, f.log);
  progress.Done();
  in.reference = ReadGnss(f.gnss, f.gnss_options);
  return in;
}

VerifyOptions OptionsFor(const CLI::App& cmd,
                         const VerifyFlags& f,
                         const GnssTrack& reference) {
  VerifyOptions options = f.options;
  if (f.time_offset_s) {
    if (cmd.count(std::string(FlagName(Option::kTimeAlign))) > 0 &&
        options.time_align != TimeAlignMode::kOffset) {
      throw Error("--time-offset goes with --time-align offset (or no --time-align)");
    }
    options.time_align = TimeAlignMode::kOffset;
    options.time_offset_s = *f.time_offset_s;
  } else if (options.time_align == TimeAlignMode::kOffset) {
    throw Error("--time-align offset needs --time-offset SECONDS");
  }
  options.integrate.use_gyro = !f.no_gyro;
  options.integrate.zero_velocity_updates = !f.no_zupt;
  // Gravity: as given; else normal gravity where the reference starts.
  if (!f.gravity.gravity_mps2 && !f.gravity.latitude_deg && reference.origin) {
    options.integrate.gravity_mps2 =
        NormalGravityMps2(reference.origin->latitude_deg, reference.origin->height_m);
  } else {
    options.integrate.gravity_mps2 = f.gravity.Resolve();
  }
  return options;
}

// The paths first, so that the result can name them for `mpcal report`.
void WriteOutputs(const VerifyFlags& f, const VerifyResult& result) {
  std::vector<std::pair<std::string, std::string>> trajectories;
  if (!f.trajectory_prefix.empty()) {
    auto write = [&](const std::string& role, const std::string& csv) {
      const std::string path = TrajectoryPath(f.trajectory_prefix, role);
      WriteFileAtomically(path, csv);
      trajectories.emplace_back(role, RelativeTo(path, f.output));
    };
    write("reference", PathToCsv(result.reference_path, result.reference_quality));
    write("raw", PathToCsv(result.raw_path));
    if (result.corrected_path) write("corrected", PathToCsv(*result.corrected_path));
  }
  WriteFileAtomically(f.output, VerificationToJson(result, trajectories));
}

// The inputs, the clocks and how the walk was integrated: for -v.
void PrintDetail(std::FILE* out,
                 const VerifyFlags& f,
                 const VerifyInputs& in,
                 const VerifyResult& result) {
  fmt::print(out,
             "IMU {} ({} samples{}) vs reference {} ({} epochs, {}); clocks: {}, offset "
             "{:.3f} s, {:.1f} s in common\n",
             f.imu,
             in.imu.size(),
             in.imu.gyro_radps.empty() ? "" : ", with gyroscope",
             f.gnss,
             result.reference.epochs,
             ToString(in.reference.time_system),
             ToString(result.time.method),
             result.time.offset_s,
             result.time.overlap_end_s - result.time.overlap_start_s);
  fmt::print(
      out,
      "attitude: {} ({:.2f} deg from z-up), {}; gravity {:.5f} m/s2; {:.1f} s initial "
      "rest, {}\n",
      result.mount == MountMode::kLevel ? "levelled at the initial rest"
                                        : "z up as stated",
      result.initial_tilt_raw_rad * 180.0 / M_PI,
      result.gyro_used ? "propagated by the gyroscope" : "fixed (no rotation)",
      result.gravity_mps2,
      result.initial_rest_s,
      Count(result.stops, "still stretch", "still stretches"));
}

void PrintSummary(std::FILE* out,
                  const VerifyFlags& f,
                  const VerifyInputs& in,
                  const VerifyResult& result) {
  if (f.verbose) PrintDetail(out, f, in, result);
  fmt::print(out,
             "  {:<10} {:>12} {:>12} {:>12} {:>12}\n",
             "(m)",
             "start-end",
             "rms horiz",
             "max horiz",
             "path length");
  fmt::print(out,
             "  {:<10} {:>12.2f} {:>12} {:>12} {:>12.1f}\n",
             "reference",
             result.reference.start_end_distance_m,
             "",
             "",
             result.reference.path_length_m);
  PrintRow(out, "raw", result.raw);
  if (result.corrected) PrintRow(out, "corrected", *result.corrected);
  fmt::print(out, "\n{}", FormatChecks(JudgeVerification(result), out));
  fmt::print(
      out, "wrote {}\n", f.output == "-" ? "the result to standard output" : f.output);
}

void RunVerify(const CLI::App& cmd, VerifyFlags& f) {
  std::vector<std::string> outputs = {f.output};
  if (!f.trajectory_prefix.empty()) {
    for (const char* role : {"reference", "raw", "corrected"}) {
      outputs.push_back(TrajectoryPath(f.trajectory_prefix, role));
    }
  }
  for (const std::string& out : outputs) CheckOutput(out, {f.imu, f.gnss, f.calibration});
  const VerifyInputs in = ReadInputs(cmd, f);
  const VerifyOptions options = OptionsFor(cmd, f, in.reference);
  // A walk in g read as m/s² integrates to a tenth of the distance: the
  // same units check as calibrate's (|a| stays near g while walking too).
  WithDetectWords([&] { CheckUnits(in.imu, options.integrate.gravity_mps2); });
  VerifyResult result = Verify(in.imu, in.reference, in.calibration, options);
  // The findings in this command's words, for the result file and the terminal.
  for (std::size_t i = 0; i < result.findings.size(); ++i) {
    result.warnings[i] = ExplainVerifyFinding(result.findings[i]);
  }
  WriteOutputs(f, result);
  PrintWarnings(in.imu.warnings);
  PrintWarnings(in.reference.warnings);
  PrintWarnings(result.warnings);
  // The result may be on standard output: then the summary goes to stderr.
  PrintSummary(f.output == "-" ? stderr : stdout, f, in, result);
}

void AddInputOutputOptions(CLI::App* cmd, VerifyFlags* f) {
  cmd->add_option("--imu", f->imu, "The walk's IMU log (as for calibrate; '-': stdin)")
      ->check(InputPath)
      ->required();
  cmd->add_option("--gnss",
                  f->gnss,
                  "The reference: RTKLIB .pos (GPST/UTC; lat/lon/height or ECEF), NMEA "
                  "GGA, or CSV with a t,lat,lon,h or t,e,n,u header")
      ->check(InputPath)
      ->required();  // a missing file is input (exit 1), reported by ReadGnss
  cmd->add_option("--calib",
                  f->calibration,
                  "Calibration file (JSON): also integrate the corrected readings")
      ->check(InputPath);
  cmd->add_option("-o,--output", f->output, "Result file (JSON); '-' for standard output")
      ->check(OutputPath)
      ->required();
  cmd->add_option(
         "--trajectory-csv",
         f->trajectory_prefix,
         "Also write PREFIX-reference.csv, PREFIX-raw.csv and PREFIX-corrected.csv "
         "(t_s,e_m,n_m,u_m on the reference's clock and frame) for plotting")
      ->check(OutputPath);
}

void AddIntegrationOptions(CLI::App* cmd, VerifyFlags* f) {
  const std::vector<std::pair<std::string, MountMode>> mounts{
      {"level", MountMode::kLevel}, {"z-up", MountMode::kZUp}};
  cmd->add_option(
         std::string(FlagName(Option::kMount)),
         f->options.integrate.mount,
         "Initial attitude: level (from the initial rest; absorbs a constant bias "
         "while the sensor does not rotate) or z-up (the sensor's z axis along an "
         "upright pole, the paper's setting)")
      ->transform(OneOf(mounts))
      ->default_str("level")
      ->group("Integration");
  cmd->add_flag("--no-gyro",
                f->no_gyro,
                "Ignore gyroscope columns (attitude fixed after the start)")
      ->group("Integration");
  cmd->add_flag("--no-zupt", f->no_zupt, "No zero-velocity updates at stops")
      ->group("Integration");
  cmd->add_option(
         "--still-window", f->options.still.window_s, "Still test: moving window (s)")
      ->capture_default_str()
      ->check(PositiveNumber)
      ->group("Integration");
  cmd->add_option("--still-threshold",
                  f->options.still.threshold_factor,
                  "Still test: threshold as a multiple of the quiet level")
      ->capture_default_str()
      ->check(CLI::Range(1.0, 100.0))
      ->group("Integration");
  cmd->add_option("--heading-distance",
                  f->options.heading_distance_m,
                  "The initial heading is taken over this distance of the reference (m)")
      ->capture_default_str()
      ->check(PositiveNumber)
      ->group("Integration");
}

void AddTimeOptions(CLI::App* cmd, VerifyFlags* f) {
  const std::vector<std::pair<std::string, TimeAlignMode>> aligns{
      {"auto", TimeAlignMode::kAuto},
      {"common", TimeAlignMode::kCommonClock},
      {"offset", TimeAlignMode::kOffset},
      {"motion", TimeAlignMode::kMotionStart}};
  cmd->add_option(
         std::string(FlagName(Option::kTimeAlign)),
         f->options.time_align,
         "Clocks: common (one clock), offset (--time-offset), motion (from the start "
         "of motion in both) or auto (common when the spans overlap, else motion)")
      ->transform(OneOf(aligns))
      ->default_str("auto")
      ->group("Time");
  cmd->add_option(std::string(FlagName(Option::kTimeOffset)),
                  f->time_offset_s,
                  "t_reference = t_imu + SECONDS (e.g. 18 for a UTC log against GPST)")
      ->group("Time");
}

void AddReferenceOptions(CLI::App* cmd, VerifyFlags* f) {
  const std::vector<std::pair<std::string, GnssFormat>> formats{
      {"auto", GnssFormat::kAuto},
      {"pos", GnssFormat::kRtklibPos},
      {"nmea", GnssFormat::kNmea},
      {"csv", GnssFormat::kCsv}};
  cmd->add_option(std::string(FlagName(Option::kGnssFormat)),
                  f->gnss_options.format,
                  "Format of the reference: auto, pos, nmea or csv")
      ->transform(OneOf(formats))
      ->default_str("auto")
      ->group("Reference");
  cmd->add_option(
         "--max-q",
         f->gnss_options.max_rtklib_quality,
         "Drop reference epochs with a worse RTKLIB Q (1 fix, 2 float, 5 single); "
         "0 keeps all")
      ->capture_default_str()
      ->check(CLI::Range(0, 6))
      ->group("Reference");
}

}  // namespace

void AddVerifyCommand(CLI::App& root) {
  auto f = std::make_shared<VerifyFlags>();
  CLI::App* cmd =
      root.add_subcommand("verify",
                          "Field verification (the paper's section 5.2): integrate a "
                          "walk around a closed loop "
                          "raw and corrected, and compare both with a GNSS reference");
  cmd->add_flag("-v,--verbose",
                f->verbose,
                "Also print the inputs, the clocks' alignment and how the walk was "
                "integrated (attitude, gravity, initial rest, stops)");
  AddInputOutputOptions(cmd, f.get());
  AddIntegrationOptions(cmd, f.get());
  AddTimeOptions(cmd, f.get());
  AddReferenceOptions(cmd, f.get());
  AddLogOptions(*cmd, f->log);
  AddGravityOptions(*cmd, f->gravity);
  cmd->footer(
      "Gravity defaults to the WGS84 normal gravity at the reference's first fix.\n"
      "Examples:\n"
      "  mpcal simulate walk --preset mti-g --turn -o walk.csv --gnss ref.pos --truth "
      "t.json\n"
      "  mpcal verify --imu walk.csv --gnss ref.pos --calib t.json -o result.json\n"
      "  mpcal verify --imu imu.csv --columns t=0,ax=1,ay=2,az=3,gx=4,gy=5,gz=6 --units "
      "g \\\n"
      "      --gnss walk.pos -o result.json --trajectory-csv walk");
  cmd->callback([cmd, f] { RunVerify(*cmd, *f); });
}

}  // namespace mpcal::cli
