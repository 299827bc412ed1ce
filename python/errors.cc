// mpcal::Error as the Python exception mpcal.Error: the library's kind,
// figures and advice become attributes, the advice spelled as the keyword
// arguments of the Python functions (never as command-line flags).
#include "errors.h"

#include <charconv>
#include <exception>
#include <string>
#include <string_view>
#include <utility>

#include "mpcal/calibrate.h"
#include "mpcal/error.h"
#include "mpcal/not_finite.h"
#include "mpcal/units.h"

namespace mpcal::python {
namespace {

std::string_view KindName(ErrorKind kind) {
  switch (kind) {
    case ErrorKind::kInput:
      return "input";
    case ErrorKind::kIo:
      return "io";
    case ErrorKind::kOption:
      return "option";
    case ErrorKind::kColumns:
      return "columns";
    case ErrorKind::kUnits:
      return "units";
    case ErrorKind::kTime:
      return "time";
    case ErrorKind::kFormat:
      return "format";
    case ErrorKind::kSession:
      return "session";
  }
  return "input";
}

std::string_view StageName(Stage stage) {
  switch (stage) {
    case Stage::kNone:
      return "";
    case Stage::kDetect:
      return "detect";
    case Stage::kCalibrate:
      return "calibrate";
    case Stage::kApply:
      return "correct";
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

// A value the library suggests, as Python would take it: a number when it
// reads as one, else the text.
py::object SettingValue(const std::string& text) {
  if (text.empty()) return py::none();
  double v = 0.0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, v);
  if (ec == std::errc() && ptr == end) return py::float_(v);
  return py::str(text);
}

py::dict Figures(const Error& e) {
  py::dict figures;
  if (const auto* units = dynamic_cast<const UnitsError*>(&e)) {
    const UnitsError::Finding& f = units->finding();
    figures["units"] = std::string(ToString(f.units));
    figures["median_magnitude"] = f.median_magnitude;
    figures["gravity_mps2"] = f.gravity_mps2;
    static constexpr const char* kGuess[] = {
        "unknown", "g", "mps2", "counts", "gravity_removed"};
    figures["looks_like"] = kGuess[static_cast<int>(f.guess)];
  }
  if (const auto* bad = dynamic_cast<const NotFiniteError*>(&e)) {
    // The argument of the Python functions that holds the column.
    static constexpr const char* kArgument[] = {"t", "accel", "gyro"};
    figures["argument"] = kArgument[static_cast<int>(bad->column())];
    figures["row"] = bad->row();
  }
  if (const auto* session = dynamic_cast<const SessionError*>(&e)) {
    static constexpr const char* kProblem[] = {
        "no_positions", "too_few_positions", "counts_not_spread"};
    figures["problem"] = kProblem[static_cast<int>(session->problem())];
    figures["positions"] = session->detection().intervals.size();
    figures["longest_still_s"] = session->detection().longest_still_s;
    figures["still_fraction"] = session->detection().still_fraction;
  }
  return figures;
}

}  // namespace

std::string_view KeywordOf(Option option) {
  switch (option) {
    case Option::kNone:
      return "";
    case Option::kLogColumns:
      return "columns";
    case Option::kLogUnits:
      return "units";
    case Option::kLogTimeUnit:
      return "time_unit";
    case Option::kLogRate:
      return "rate_hz";
    case Option::kLogGyroUnits:
      return "gyro_units";
    case Option::kLogTopic:
      return "topic";
    case Option::kLogRecordingTime:
      return "time";
    case Option::kAccelTopic:
      return "accel_topic";
    case Option::kGyroTopic:
      return "gyro_topic";
    case Option::kGyroLog:
      return "gyro_log";
    case Option::kGyroLogColumns:
      return "gyro_columns";
    case Option::kGravity:
      return "gravity";
    case Option::kLatitude:
      return "latitude_deg";
    case Option::kHeight:
      return "height_m";
    case Option::kModel:
      return "model";
    case Option::kRobust:
      return "robust";
    case Option::kDetectWindow:
      return "window_s";
    case Option::kDetectMinStatic:
      return "min_static_s";
    case Option::kDetectSettle:
      return "settle_s";
    case Option::kDetectThreshold:
      return "threshold";
    case Option::kDetectMaxStill:
      return "max_still_g";
    case Option::kDetectMergeGap:
      return "merge_gap_s";
    case Option::kDetectMergeAngle:
      return "merge_angle_deg";
    case Option::kSensorRange:
      return "range_g";
    case Option::kTimeOffset:
      return "time_offset_s";
    case Option::kTimeAlign:
      return "time_align";
    case Option::kMount:
      return "mount";
    case Option::kGnssFormat:
      return "gnss_format";
    case Option::kVerifyTrajectories:
      return "verify_trajectories";
  }
  return "";
}

Advice Suggest(Option option, std::string value) {
  Advice advice;
  advice.settings.push_back(Setting{option, std::move(value)});
  return advice;
}

Advice Suggest(Option option, Option alternative) {
  Advice advice = Suggest(option);
  advice.settings.push_back(Setting{alternative, ""});
  return advice;
}

py::dict AdviceSettings(const Advice& advice) {
  py::dict settings;
  for (const Setting& s : advice.settings) {
    settings[py::str(std::string(KeywordOf(s.option)))] = SettingValue(s.value);
  }
  return settings;
}

py::object StageOf(const Advice& advice) {
  if (advice.stage == Stage::kNone) return py::none();
  return py::str(std::string(StageName(advice.stage)));
}

void RegisterErrorTranslator() {
  // pybind11's translator type takes the exception_ptr by value.
  // NOLINTNEXTLINE(performance-unnecessary-value-param)
  py::register_exception_translator([](std::exception_ptr thrown) {
    try {
      if (thrown) std::rethrow_exception(thrown);
    } catch (const Error& e) {
      const py::object cls = py::module_::import("mpcal._errors").attr("Error");
      const py::object exception = cls(e.what(),
                                       std::string(KindName(e.kind())),
                                       AdviceSettings(e.advice()),
                                       StageOf(e.advice()),
                                       e.advice().stage_input,
                                       Figures(e));
      PyErr_SetObject(cls.ptr(), exception.ptr());
    }
  });
}

}  // namespace mpcal::python
