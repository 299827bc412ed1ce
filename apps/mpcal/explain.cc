#include "explain.h"

#include <array>
#include <utility>

#include <fmt/format.h>

namespace mpcal::cli {
namespace {

struct FlagSpelling {
  Option option;
  std::string_view flag;
  std::string_view placeholder;
};

// Every Option the library can point at, and the flag that sets it. The flag
// declarations (cli_options.cc and the subcommands) take their names from
// here, so renaming a flag renames the advice with it.
constexpr std::array kFlags{
    FlagSpelling{Option::kNone, "", ""},
    FlagSpelling{Option::kLogColumns, "--columns", "t=..,ax=..,ay=..,az=.."},
    FlagSpelling{Option::kLogUnits, "--units", "UNITS"},
    FlagSpelling{Option::kLogTimeUnit, "--time-unit", "UNIT"},
    FlagSpelling{Option::kLogRate, "--rate", "HZ"},
    FlagSpelling{Option::kLogGyroUnits, "--gyro-units", "UNITS"},
    FlagSpelling{Option::kLogTopic, "--topic", "TOPIC"},
    FlagSpelling{Option::kLogRecordingTime, "--time", "TIME"},
    FlagSpelling{Option::kGyroLog, "--gyro-log", "FILE"},
    FlagSpelling{Option::kGyroLogColumns, "--gyro-columns", "t=..,gx=..,gy=..,gz=.."},
    FlagSpelling{Option::kAccelTopic, "--accel-topic", "TOPIC"},
    FlagSpelling{Option::kGyroTopic, "--gyro-topic", "TOPIC"},
    FlagSpelling{Option::kGravity, "--gravity", "MPS2"},
    FlagSpelling{Option::kLatitude, "--latitude", "DEG"},
    FlagSpelling{Option::kHeight, "--height", "M"},
    FlagSpelling{Option::kModel, "--model", "MODEL"},
    FlagSpelling{Option::kRobust, "--robust", "LOSS"},
    FlagSpelling{Option::kDetectWindow, "--window", "S"},
    FlagSpelling{Option::kDetectMinStatic, "--min-static", "S"},
    FlagSpelling{Option::kDetectSettle, "--settle", "S"},
    FlagSpelling{Option::kDetectThreshold, "--threshold", "K"},
    FlagSpelling{Option::kDetectMaxStill, "--max-still", "S"},
    FlagSpelling{Option::kDetectMergeGap, "--merge-gap", "S"},
    FlagSpelling{Option::kDetectMergeAngle, "--merge-angle", "DEG"},
    FlagSpelling{Option::kSensorRange, "--range", "G"},
    FlagSpelling{Option::kTimeOffset, "--time-offset", "SECONDS"},
    FlagSpelling{Option::kTimeAlign, "--time-align", "MODE"},
    FlagSpelling{Option::kMount, "--mount", "MOUNT"},
    FlagSpelling{Option::kGnssFormat, "--gnss-format", "FORMAT"},
    FlagSpelling{Option::kVerifyTrajectories, "--verify-trajectories", "PREFIX"},
};

const FlagSpelling& Spelling(Option option) {
  for (const auto& spelling : kFlags) {
    if (spelling.option == option) return spelling;
  }
  return kFlags.front();
}

}  // namespace

std::string_view FlagName(Option option) { return Spelling(option).flag; }

std::string_view FlagPlaceholder(Option option) { return Spelling(option).placeholder; }

std::string FlagWithValue(const Setting& setting) {
  const auto& spelling = Spelling(setting.option);
  return fmt::format(
      "{} {}",
      spelling.flag,
      setting.value.empty() ? std::string(spelling.placeholder) : setting.value);
}

std::string_view SubcommandName(Stage stage) {
  switch (stage) {
    case Stage::kNone:
      return "";
    case Stage::kDetect:
      return "detect";
    case Stage::kCalibrate:
      return "calibrate";
    case Stage::kApply:
      return "apply";
    case Stage::kVerify:
      return "verify";
    case Stage::kRepeat:
      return "repeat";
    case Stage::kNoise:
      return "noise";
    case Stage::kSimulate:
      return "simulate";
    case Stage::kReport:
      return "report";
  }
  return "";
}

std::string ExplainAdvice(const Advice& advice) {
  if (advice.empty()) return "";
  std::string settings;
  const std::string_view joint = advice.stage == Stage::kNone ? " or " : " ";
  for (const auto& setting : advice.settings) {
    if (!settings.empty()) settings += joint;
    settings += FlagWithValue(setting);
  }
  if (advice.stage == Stage::kNone) return "give " + settings;
  std::string command = fmt::format("mpcal {}", SubcommandName(advice.stage));
  if (!advice.stage_input.empty()) command += " " + advice.stage_input;
  if (!settings.empty()) command += " " + settings;
  return fmt::format("run '{}'", command);
}

std::string Explain(const Error& error) {
  // A file of another kind than expected: name the command that writes it.
  if (error.kind() == ErrorKind::kFormat && error.advice().settings.empty() &&
      error.advice().stage != Stage::kNone) {
    return fmt::format("{}; expected JSON written by 'mpcal {}'",
                       error.what(),
                       SubcommandName(error.advice().stage));
  }
  const std::string advice = ExplainAdvice(error.advice());
  if (advice.empty()) return error.what();
  return fmt::format("{}; {}", error.what(), advice);
}

}  // namespace mpcal::cli
