// mpcal detect: the static positions of a log and whether they are enough to
// calibrate, before running `calibrate`.
#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "cli_options.h"
#include "colour.h"
#include "command.h"
#include "explain_detect.h"
#include "mpcal/atomic_file.h"
#include "mpcal/calibrate.h"
#include "mpcal/count.h"
#include "mpcal/coverage.h"
#include "mpcal/detect.h"
#include "mpcal/error.h"
#include "mpcal/gyro_log.h"
#include "mpcal/log_reader.h"
#include "progress.h"

namespace mpcal::cli {
namespace {

struct DetectFlags {
  std::string input;
  std::string json;
  GyroLogFlags gyro_log;
  LogOptions log;
  GravityFlags gravity;
  CalibrateOptions calibrate;
  bool verbose = false;
};

std::string JoinDirections(const std::vector<int>& idx) {
  if (idx.empty()) return "none";
  std::string out;
  for (std::size_t k = 0; k < idx.size(); ++k) {
    if (k > 0) out += ", ";
    out += CanonicalDirections()[static_cast<std::size_t>(idx[k])].down;
  }
  return out;
}

void PrintDetection(const Recording& rec,
                    const DetectResult& det,
                    const DetectOptions& o) {
  const std::string unit(UnitSymbol(rec.units));
  fmt::print("static detection: window {} s ({}), min {} s, settle {} s\n",
             o.window_s,
             Count(det.window_samples, "sample"),
             o.min_static_s,
             o.settle_s);
  fmt::print(
      "  quiet level {:.4g} {}, threshold {:.4g} {} ({}), {:.0f}% of samples still\n",
      det.quiet_level,
      unit,
      det.threshold,
      unit,
      det.threshold_capped ? fmt::format("capped at {} g", o.max_still_g)
                           : fmt::format("{} x quiet level", o.threshold_factor),
      100.0 * det.still_fraction);
  fmt::print(
      "  {}; {} shorter than {} s dropped, {} "
      "merged across a short bump; longest still stretch {:.1f} s\n",
      Count(det.intervals.size(), "static position"),
      Count(det.dropped_short, "still stretch", "still stretches"),
      o.min_static_s,
      det.merged,
      det.longest_still_s);
}

void PrintIntervals(const Recording& rec,
                    const DetectResult& det,
                    const CoverageResult& cov) {
  if (det.intervals.empty()) return;
  const double t0 = rec.time_s.front();
  // Enough decimals for the noise of the unit: counts need none, m/s² four.
  const int prec = rec.units == AccelUnits::kCounts ? 1 : 4;
  fmt::print("\n{:>3} {:>9} {:>9} {:>7} {:>11} {:>11} {:>11} {:>9} {:>7}\n",
             "#",
             "start s",
             "end s",
             "dur s",
             "mean x",
             "mean y",
             "mean z",
             "noise",
             "turn deg");
  for (std::size_t k = 0; k < det.intervals.size(); ++k) {
    const StaticInterval& iv = det.intervals[k];
    const double turn = cov.angle_to_previous_deg[k];
    fmt::print(
        "{:>3} {:>9.2f} {:>9.2f} {:>7.2f} {:>11.{}f} {:>11.{}f} {:>11.{}f} {:>9.3g} "
        "{:>7}\n",
        k + 1,
        iv.start_s - t0,
        iv.end_s - t0,
        iv.duration_s(),
        iv.mean.x(),
        prec,
        iv.mean.y(),
        prec,
        iv.mean.z(),
        prec,
        iv.noise(),
        std::isfinite(turn) ? fmt::format("{:.1f}", turn) : "-");
  }
  fmt::print(
      "times from the first sample (t = {:.6g} s in the log's clock); mean and noise "
      "(norm "
      "of the per-axis std) in {}; turn: angle from the previous position\n",
      t0,
      UnitSymbol(rec.units));
}

void PrintCoverage(const CoverageResult& cov, const CoverageOptions& o) {
  if (cov.positions == 0) return;
  const std::string unit(UnitSymbol(o.units));
  fmt::print(
      "\ncoverage for --model {}: {}, {} (>{} deg "
      "apart)\n",
      ToString(o.model),
      Count(cov.positions, "position"),
      Count(cov.distinct_positions, "distinct orientation"),
      o.distinct_deg);
  fmt::print("  offset ({:.6g}, {:.6g}, {:.6g}) {}, 1 g = {:.5g} {} ({})\n",
             cov.normalisation.centre.x(),
             cov.normalisation.centre.y(),
             cov.normalisation.centre.z(),
             unit,
             cov.normalisation.radius,
             unit,
             cov.normalisation.fitted ? "sphere fitted to the means"
                                      : "not fitted: too few "
                                        "positions, nominal");
  fmt::print("  cube directions within {} deg: {} of 26 (named by what points down)\n",
             o.near_deg,
             cov.covered.size());
  fmt::print("    covered: {}\n", JoinDirections(cov.covered));
  fmt::print("    missing: {}\n", JoinDirections(cov.missing));
  fmt::print("  axis  up (closest)   down (closest)  largest tilt gap\n");
  for (int i = 0; i < 3; ++i) {
    const AxisCoverage& ax = cov.axes[static_cast<std::size_t>(i)];
    fmt::print("  +{}    {:<3} {:>5.1f} deg  {:<3} {:>5.1f} deg   {:>5.1f} deg\n",
               static_cast<char>('x' + i),
               ax.near_up ? "yes" : "no",
               ax.closest_up_deg,
               ax.near_down ? "yes" : "no",
               ax.closest_down_deg,
               ax.largest_gap_deg);
  }
  fmt::print("  largest empty cap {:.0f} deg; observability {:.3g}\n",
             cov.largest_empty_cap_deg,
             cov.observability);
}

// The turns between the positions, as the gyroscope measured them.
// `logged`: the gyroscope's units in the log (a log in deg/s is read as rad/s).
void PrintTurns(const Recording& rec,
                const std::vector<Turn>& turns,
                double scale,
                GyroUnits logged) {
  if (turns.empty()) return;
  const double t0 = rec.time_s.front();
  fmt::print("\n{:>5} {:>9} {:>7} {:>9} {:>7} {:>7} {:>7} {:>8}\n",
             "turn",
             "start s",
             "dur s",
             "angle deg",
             "axis x",
             "axis y",
             "axis z",
             "tilt deg");
  for (const Turn& t : turns) {
    fmt::print("{:>5} {:>9.2f} {:>7.2f} {:>9.1f} {:>7.3f} {:>7.3f} {:>7.3f} {:>8.1f}\n",
               fmt::format("{}-{}", t.from + 1, t.from + 2),
               t.start_s - t0,
               t.duration_s(),
               t.angle_deg,
               t.axis.x(),
               t.axis.y(),
               t.axis.z(),
               t.tilt_deg);
  }
  fmt::print(
      "turns between neighbouring positions from the gyroscope ({}), bias measured at "
      "the two positions taken out; axis in the sensor frame at the start; tilt: angle "
      "between the gravity directions before and after\n",
      rec.gyro_units == GyroUnits::kCounts
          ? fmt::format("nominal scale {:.5g} rad/s per count, fitted to the tilts",
                        scale)
          : fmt::format("in {}", ToString(logged)));
}

void Run(DetectFlags& f) {
  ThrowIfInvalid(f.calibrate.detect.Validate(), "detect");
  if (!f.json.empty()) CheckOutput(f.json, {f.input, f.gyro_log.path});

  TerminalProgress progress("reading " + f.input);
  f.log.progress = progress.Callback();
  Recording rec = ReadLog(f.input, WithAccelTopic(f.log, f.gyro_log));
  progress.Done();
  const MergedStreams streams = MergeGyroLogFile(rec, f.input, f.gyro_log, f.log);
  if (!streams.summary.empty()) fmt::print("{}\n", streams.summary);
  for (const auto& w : streams.warnings) {
    fmt::print("  note: {}\n", w);
  }
  WithDetectWords([&] { CheckUnits(rec, f.gravity.Resolve()); });

  const DetectOptions& o = f.calibrate.detect;
  const DetectResult det = DetectStatic(rec, o);
  CoverageOptions co;
  co.model = f.calibrate.solve.model;
  co.units = rec.units;
  co.hold_s = std::max(10.0, std::ceil(o.min_static_s + 2 * o.settle_s + o.window_s));
  const CoverageResult cov = AssessCoverage(det, co);
  double gyro_scale = 0.0;
  const std::vector<Turn> turns = MeasureTurns(rec, det.intervals, &gyro_scale);

  const double span_s = rec.time_s.back() - rec.time_s.front();
  fmt::print("{}: {}, {:.1f} s at {:.4g} Hz, units {}\n",
             f.input,
             Count(rec.size(), "row"),
             span_s,
             det.sample_period_s > 0 ? 1.0 / det.sample_period_s : 0.0,
             UnitSymbol(rec.units));
  // On stdout with the report, so that stderr keeps to the one error line.
  for (const auto& w : rec.warnings) fmt::print("  note: {}\n", w);
  if (f.verbose) PrintDetection(rec, det, o);
  for (const auto& n : det.notes) fmt::print("  note: {}\n", ExplainNote(n));
  if (f.verbose) {
    PrintIntervals(rec, det, cov);
    PrintTurns(rec, turns, gyro_scale, f.log.gyro_units());
    PrintCoverage(cov, co);
  } else if (cov.positions > 0) {
    fmt::print("{}, {} of 26 cube directions (missing: {}){}\n",
               Count(det.intervals.size(), "static position"),
               cov.covered.size(),
               JoinDirections(cov.missing),
               turns.empty() ? "" : fmt::format(", {}", Count(turns.size(), "turn")));
  }

  if (!f.json.empty()) {
    const DetectionWords words = ExplainDetectionWords(det, cov);
    WriteFileAtomically(f.json,
                        DetectionReportJson(det, cov, co, f.input, &words, turns));
    fmt::print("\nwrote {}\n", f.json);
  }
  if (det.intervals.empty()) {
    throw Error(ErrorKind::kSession, f.input + ": " + ExplainDetection(det.finding));
  }

  const Tint tint = cov.verdict == CoverageVerdict::kGood ? Tint::kGood
                    : cov.verdict == CoverageVerdict::kUsableWithWarnings
                        ? Tint::kLookAt
                        : Tint::kDoNotUse;
  fmt::print("\nverdict: {}\n", Paint(stdout, ToString(cov.verdict), tint));
  for (const auto& p : cov.problems) fmt::print("  - {}\n", ExplainProblem(p));
  for (const auto& a : cov.advice) fmt::print("  next: {}\n", ExplainStep(a));
  if (!cov.good_enough()) throw Error(ErrorKind::kSession, ExplainSummary(cov));
  fmt::print("good enough to calibrate with --model {}: run 'mpcal calibrate {} ...'\n",
             ToString(co.model),
             f.input);
}

}  // namespace

void AddDetectCommand(CLI::App& root) {
  auto flags = std::make_shared<DetectFlags>();
  CLI::App* app = root.add_subcommand(
      "detect",
      "Find the static positions in a log, show how well they cover the sphere, and say "
      "whether they are enough to calibrate (exit 0) or what to record next (exit 1); "
      "with a gyroscope, the turns between the positions (angle, axis, duration)");
  app->add_option("INPUT", flags->input, "Log: CSV or text, '-' for standard input")
      ->check(InputPath)
      ->required();
  app->add_option("--json",
                  flags->json,
                  "Also write the intervals and the coverage as JSON (mpcal.detection/1)")
      ->check(OutputPath);
  AddLogOptions(*app, flags->log);
  AddGyroLogOptions(*app, flags->gyro_log);
  AddGravityOptions(*app, flags->gravity);
  AddCalibrateOptions(*app, flags->calibrate);
  app->add_flag(
      "-v,--verbose",
      flags->verbose,
      "Also print the detection's levels, the table of positions, the turns and "
      "the coverage of the sphere in detail");
  app->footer(
      "Examples:\n"
      "  mpcal detect session.csv\n"
      "  mpcal detect -v session.csv   (every position and turn, the coverage)\n"
      "  mpcal detect xsens_acc.mat --units counts --json positions.json\n"
      "  mpcal detect xsens_acc.mat --gyro-log xsens_gyro.mat --units counts "
      "--gyro-units counts\n"
      "  mpcal detect poses.csv --columns t=n_samples --time-unit index --rate 102.4 "
      "--model bias-scale-6\n"
      "Exit status: 0 when the session is good enough for the model, 1 otherwise (the "
      "last line says what to record next). The verdict is coloured on a terminal; "
      "set NO_COLOR=1 for plain text.");
  app->callback([flags] { Run(*flags); });
}

}  // namespace mpcal::cli
