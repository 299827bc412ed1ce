// mpcal report: the calibration, and optionally its session, repeatability
// and verification, as one self-contained HTML page.
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "cli_options.h"
#include "command.h"
#include "explain.h"
#include "mpcal/atomic_file.h"
#include "mpcal/calibrate.h"
#include "mpcal/error.h"
#include "mpcal/report.h"

namespace mpcal::cli {
namespace {

struct ReportFlags {
  ReportFiles files;
  std::string output;
};

// The command line again, so that the report says how to make it anew.
std::string CommandLine(const ReportFlags& f) {
  std::string line = "mpcal report";
  auto add = [&line](const char* flag, const std::string& value) {
    if (!value.empty()) line += fmt::format(" {} {}", flag, value);
  };
  add("--calib", f.files.calibration);
  add("--session", f.files.session);
  if (!f.files.session.empty()) {
    add("--columns", f.files.log.columns);
    if (f.files.log.units != AccelUnits::kMps2) {
      add("--units", std::string(ToString(f.files.log.units)));
    }
    if (f.files.log.time_unit != TimeUnit::kAuto) {
      add("--time-unit", std::string(ToString(f.files.log.time_unit)));
    }
    if (f.files.log.rate_hz > 0) add("--rate", fmt::format("{}", f.files.log.rate_hz));
    if (f.files.log.gyro_in_dps) line += " --gyro-units dps";
  }
  add("--repeat", f.files.repeatability);
  add("--verify", f.files.verification);
  add("--verify-trajectories", f.files.verification_trajectories);
  add("--noise", f.files.noise);
  add("-o", f.output);
  return line;
}

void Run(const ReportFlags& f) {
  if (f.files.calibration.empty() && f.files.session.empty() &&
      f.files.repeatability.empty() && f.files.verification.empty() &&
      f.files.noise.empty()) {
    throw Error(
        "nothing to report: give at least one of --calib, --session, --repeat, "
        "--verify, --noise");
  }
  if (!f.files.verification_trajectories.empty() && f.files.verification.empty()) {
    throw Error("--verify-trajectories needs --verify (the result they belong to)");
  }
  ThrowIfInvalid(f.files.Validate(), "mpcal report");
  CheckOutput(f.output,
              {f.files.calibration,
               f.files.session,
               f.files.repeatability,
               f.files.verification,
               f.files.noise});
  ReportInputs inputs = LoadReportInputs(f.files);
  // A counts log read as m/s² would plot ±20,000 "m/s²": calibrate's check.
  if (inputs.session) CheckUnits(inputs.session->recording, kStandardGravityMps2);
  inputs.command_line = CommandLine(f);
  // Advice in the page as the command to run: "mpcal report --verify-trajectories
  // PREFIX".
  inputs.explain_advice = [](const Advice& advice) {
    if (advice.stage == Stage::kNone) return ExplainAdvice(advice);
    std::string command = fmt::format("mpcal {}", SubcommandName(advice.stage));
    for (const Setting& setting : advice.settings)
      command += " " + FlagWithValue(setting);
    return command;
  };
  WriteReport(f.output, inputs);
  if (f.output == "-") return;
  // In the order of the page (RenderReport).
  std::vector<std::string_view> sections;
  for (const auto& [present, name] :
       {std::pair{inputs.calibration.has_value(), "calibration"},
        std::pair{inputs.calibration && inputs.calibration->gyroscope, "gyroscope"},
        std::pair{inputs.session.has_value(), "session"},
        std::pair{inputs.repeatability.has_value(), "repeatability"},
        std::pair{inputs.verification.has_value(), "verification"},
        std::pair{inputs.noise.has_value(), "noise"}}) {
    if (present) sections.push_back(name);
  }
  fmt::print("wrote {} ({})\n", f.output, fmt::join(sections, ", "));
}

}  // namespace

void AddReportCommand(CLI::App& root) {
  auto f = std::make_shared<ReportFlags>();
  CLI::App* cmd = root.add_subcommand(
      "report",
      "Write an HTML report (self-contained: opens from disk, fetches nothing)");
  cmd->add_option("--calib",
                  f->files.calibration,
                  "Calibration file (JSON) from 'mpcal calibrate': parameters, fit, "
                  "residual of every position, orientations covered")
      ->check(InputPath);
  cmd->add_option("--session",
                  f->files.session,
                  "The recording the calibration came from: readings against time with "
                  "the static positions shaded (read with the log options below)")
      ->check(InputPath);
  AddLogOptions(*cmd, f->files.log);
  cmd->add_option("--repeat",
                  f->files.repeatability,
                  "Repeatability table from 'mpcal repeat --json'")
      ->check(InputPath);
  cmd->add_option(
         "--verify", f->files.verification, "Verification result from 'mpcal verify -o'")
      ->check(InputPath);
  cmd->add_option(std::string(FlagName(Option::kVerifyTrajectories)),
                  f->files.verification_trajectories,
                  "PREFIX given to 'mpcal verify --trajectory-csv': plots "
                  "PREFIX-reference.csv, PREFIX-raw.csv, PREFIX-corrected.csv")
      ->check(InputPath);
  cmd->add_option(
         "--noise",
         f->files.noise,
         "Noise analysis from 'mpcal noise --json': Allan deviation of each axis "
         "with its band and fitted terms, the terms table")
      ->check(InputPath);
  cmd->add_option(
         "-o,--output", f->output, "The HTML file to write ('-': standard output)")
      ->check(OutputPath)
      ->required();
  cmd->footer(
      "Each section appears when its input is given; at least one is needed.\n"
      "Example:\n"
      "  mpcal simulate static --preset mti-g --seed 1 -o s.csv --truth t.json\n"
      "  mpcal calibrate s.csv -o c.json\n"
      "  mpcal report --calib c.json --session s.csv -o report.html\n"
      "  mpcal report --calib c.json --repeat rep.json --verify result.json "
      "--verify-trajectories walk -o report.html\n"
      "  mpcal report --noise noise.json -o noise.html");
  cmd->callback([f] { Run(*f); });
}

}  // namespace mpcal::cli
