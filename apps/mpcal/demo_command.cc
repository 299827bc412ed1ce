// mpcal demo: the main job with no input. Simulates a session of a device
// preset, calibrates it exactly as `mpcal calibrate` would, and prints the
// estimate beside the truth and the Cramér-Rao bound, so a new user sees in
// one screen what mpcal does and how close to the limit it gets. Then the
// rest of the workflow on the same simulated device: two more power-ups
// (repeatability) and a walked loop against GNSS (verification), all in one
// report.
#include <cmath>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "calibration_table.h"
#include "cli_options.h"
#include "command.h"
#include "explain_checks.h"
#include "gyro_table.h"
#include "mpcal/calibrate.h"
#include "mpcal/calibration_file.h"
#include "mpcal/gnss.h"
#include "mpcal/gyro.h"
#include "mpcal/repeat.h"
#include "mpcal/report.h"
#include "mpcal/simulate.h"
#include "mpcal/simulate_walk.h"
#include "mpcal/verdict.h"
#include "mpcal/verify.h"
#include "simulated_bound.h"

namespace mpcal::cli {
namespace {

struct DemoFlags {
  std::string preset = "mti-g";
  std::uint64_t seed = 1;
  std::string output_dir = "mpcal-demo";
  bool verbose = false;
};

// The calibrated session counts as the first power-up; two more of the same
// device follow, each with its bias drawn anew.
constexpr int kTrials = 3;

RepeatabilityResult DemoRepeatability(const SimulateStaticOptions& sim,
                                      const Calibration& first) {
  std::vector<Calibration> trials{first};
  const std::vector<SimulateStaticOptions> later = TrialOptions(sim, kTrials);
  for (int i = 1; i < kTrials; ++i) {
    const SimulatedSession session = SimulateStatic(later[static_cast<std::size_t>(i)]);
    trials.push_back(
        CalibrateRecording(session.recording, CalibrateOptions{}).calibration);
  }
  return AnalyzeRepeatability(trials);
}

// A loop walked with the sensor turning at each corner (gyroscope on), so
// that the accelerometer errors show in the path; the reference goes through
// the RTKLIB .pos text a user's file would hold.
VerifyResult DemoVerification(const SimulateStaticOptions& sim,
                              const Calibration& calibration) {
  SimulateWalkOptions walk_options;
  walk_options.device = sim.device;
  walk_options.seed = sim.seed;
  walk_options.turn = true;
  const SimulatedWalk walk = SimulateWalk(walk_options);
  const GnssTrack reference =
      ParseGnss(FormatRtklibPos(walk.gnss, TimeSystem::kGpst), "<simulated GNSS>");
  VerifyOptions options;
  options.integrate.gravity_mps2 = calibration.gravity_mps2;
  return Verify(walk.recording, reference, calibration, options);
}

// The gyroscope of the same session beside the accelerometer: its estimate
// against the truth and the Cramér-Rao bound of the turns.
void PrintGyroscope(const SimulatedSession& session,
                    const CalibrateResult& result,
                    bool verbose) {
  if (!result.gyro || !session.truth.gyroscope) return;
  const GyroResult& gyro = *result.gyro;
  fmt::print(
      "\n{}",
      FormatGyroTable(gyro.calibration, &*session.truth.gyroscope, "truth", verbose));
  if (verbose) fmt::print("{}", FormatGyroSummary(gyro));
  PrintWarnings(GyroFindingMessages(gyro));
  if (!gyro.converged()) return;
  const Eigen::Matrix<double, 9, 9> bound = GyroCramerRaoBound(session.recording,
                                                               result.detection.intervals,
                                                               result.calibration,
                                                               *session.truth.gyroscope);
  double sum = 0.0;
  for (int p = 0; p < 9; ++p) {
    const double err =
        gyro.calibration.m(p / 3, p % 3) - session.truth.gyroscope->m(p / 3, p % 3);
    sum += err * err / bound(p, p);
  }
  fmt::print(
      "RMS of (estimate - truth) / Cramér-Rao bound over the 9 entries of the "
      "gyroscope's M: {:.2f}\n",
      std::sqrt(sum / 9.0));
}

void Run(const DemoFlags& f) {
  SimulateStaticOptions sim;
  sim.device = FindPreset(f.preset);
  sim.seed = f.seed;
  sim.gyro = true;
  const SimulatedSession session = SimulateStatic(sim);
  fmt::print(
      "mpcal demo: a simulated {} session (accelerometer and gyroscope), {} positions "
      "held {:.0f} s each at "
      "{:.0f} Hz (seed {}), calibrated as 'mpcal calibrate' would.\n\n",
      sim.device.name,
      session.directions.size(),
      sim.dwell_s,
      session.rate_hz,
      f.seed);

  const CalibrateResult result =
      CalibrateRecording(session.recording, CalibrateOptions{});
  const Eigen::Matrix<double, 9, 1> bound =
      SimulatedBoundSigma(session, sim.initial_rest_s);
  const Eigen::Matrix<double, 9, 1> truth = ToVector(session.truth.model);
  fmt::print("{}",
             FormatParameterTable(
                 result.calibration, {{"truth", truth}, {"bound 1σ", bound}}, f.verbose));
  if (f.verbose) fmt::print("\n{}", FormatFitSummary(result));
  const Eigen::Matrix<double, 9, 1> z =
      (ToVector(result.calibration.model) - truth).cwiseQuotient(bound);
  fmt::print(
      "RMS of (estimate - truth) / Cramér-Rao bound over the 9 parameters: {:.2f} "
      "(an efficient estimator gives 1 on average)\n",
      std::sqrt(z.squaredNorm() / 9.0));
  PrintGyroscope(session, result, f.verbose);
  fmt::print("\n{}", FormatChecks(JudgeCalibration(result, CalibrateOptions{}), stdout));
  PrintWarnings(result.warnings);

  const RepeatabilityResult repeatability = DemoRepeatability(sim, result.calibration);
  fmt::print(
      "\nRepeatability over {} power-ups of this device (this session and {} more):\n{}",
      kTrials,
      kTrials - 1,
      RepeatabilityVerdict(repeatability));

  const VerifyResult verification = DemoVerification(sim, result.calibration);
  fmt::print(
      "\nWalked loop against GNSS: the end lands {:.2f} m from the start with raw "
      "readings, {:.2f} m corrected (reference {:.2f} m, path {:.0f} m).\n",
      verification.raw.start_end_distance_m,
      verification.corrected->start_end_distance_m,
      verification.reference.start_end_distance_m,
      verification.reference.path_length_m);

  std::filesystem::create_directories(f.output_dir);
  const std::string truth_path = f.output_dir + "/truth.json";
  const std::string calib_path = f.output_dir + "/calib.json";
  const std::string report_path = f.output_dir + "/report.html";
  WriteCalibrationFile(truth_path, session.truth);
  WriteCalibrationFile(calib_path, result.calibration);

  ReportInputs report;
  report.title = "mpcal demo report";
  report.calibration = result.calibration;
  report.session = ReportSession{session.recording, result.detection};
  report.repeatability = repeatability;
  report.verification = SummarizeVerification(verification);
  report.input_files = {{"Calibration file", calib_path},
                        {"Truth (simulated)", truth_path}};
  report.command_line = fmt::format(
      "mpcal demo --preset {} --seed {} --output-dir {}", f.preset, f.seed, f.output_dir);
  WriteReport(report_path, report);
  fmt::print("\nwrote {}, {} and {} (open it in a browser)\n",
             calib_path,
             truth_path,
             report_path);
}

}  // namespace

void AddDemoCommand(CLI::App& root) {
  auto flags = std::make_shared<DemoFlags>();
  CLI::App* app = root.add_subcommand(
      "demo",
      "Simulate a device (accelerometer and gyroscope), calibrate it, compare with the "
      "truth and the Cramér-Rao bound; write a report with every section");
  app->add_option("--preset", flags->preset, "Device: colibri, inertiacube3 or mti-g")
      ->capture_default_str();
  app->add_option("--seed", flags->seed, "Random seed")->capture_default_str();
  app->add_flag("-v,--verbose",
                flags->verbose,
                "Also print the diagnostics behind the checks, as 'mpcal calibrate -v' "
                "does");
  app->add_option("--output-dir",
                  flags->output_dir,
                  "Where the calibration, the truth and the report go")
      ->capture_default_str()
      ->check(OutputDirectory);
  app->footer("Example:\n  mpcal demo --preset colibri --seed 7");
  app->callback([flags] { Run(*flags); });
}

}  // namespace mpcal::cli
