// mpcal._mpcal: the library on numpy arrays. The Python package
// (python/mpcal/__init__.py) checks the arguments, names them in its
// messages and documents them; this file converts and calls the library,
// without the GIL while it works.
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include <fmt/format.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "arrays.h"
#include "detect.h"
#include "errors.h"
#include "export.h"
#include "findings.h"
#include "interrupt.h"
#include "mpcal/apply.h"
#include "mpcal/atomic_file.h"
#include "mpcal/calibrate.h"
#include "mpcal/calibration_file.h"
#include "mpcal/gravity.h"
#include "mpcal/gyro_log.h"
#include "mpcal/log_reader.h"
#include "noise.h"
#include "simulate.h"

namespace mpcal::python {
namespace {

template <typename T>
T Get(const py::dict& options, const char* key) {
  return options[key].cast<T>();
}

LogOptions LogOptionsFrom(const py::dict& o) {
  LogOptions log;
  log.columns = Get<std::string>(o, "columns");
  log.units = AccelUnitsArgument(Get<std::string>(o, "units"), "units");
  log.topic = Get<std::string>(o, "topic");
  const GyroUnits gyro =
      GyroUnitsArgument(Get<std::string>(o, "gyro_units"), "gyro_units");
  log.gyro_in_dps = gyro == GyroUnits::kDps;
  log.gyro_in_counts = gyro == GyroUnits::kCounts;
  const auto time_unit = ParseTimeUnit(Get<std::string>(o, "time_unit"));
  if (!time_unit) {
    throw Error(ErrorKind::kOption,
                fmt::format("time_unit='{}' is not a time unit: give 'auto', 's', 'ms', "
                            "'us', 'ns' or 'index'",
                            Get<std::string>(o, "time_unit")),
                Suggest(Option::kLogTimeUnit, ""));
  }
  log.time_unit = *time_unit;
  log.rate_hz = Get<double>(o, "rate_hz");
  const auto time = Get<std::string>(o, "time");
  if (time != ToString(RecordingTime::kHeader) &&
      time != ToString(RecordingTime::kReceive)) {
    throw Error(ErrorKind::kOption,
                fmt::format("time='{}': give 'header' (the messages' stamps) or "
                            "'receive' (when the recorder received them)",
                            time),
                Suggest(Option::kLogRecordingTime, "header"));
  }
  log.recording_time = time == ToString(RecordingTime::kReceive) ? RecordingTime::kReceive
                                                                 : RecordingTime::kHeader;
  if (const std::string bad = log.Validate(); !bad.empty()) {
    throw Error(ErrorKind::kOption, "read_log: " + bad);
  }
  return log;
}

py::dict ReadLogDefaults() {
  const LogOptions log;
  py::dict d;
  d["columns"] = log.columns;
  d["units"] = std::string(ToString(log.units));
  d["topic"] = log.topic;
  d["gyro_units"] = std::string(ToString(log.gyro_units()));
  d["time_unit"] = std::string(ToString(log.time_unit));
  d["rate_hz"] = log.rate_hz;
  d["time"] = std::string(ToString(log.recording_time));
  d["gyro_log"] = "";
  d["gyro_columns"] = "";
  d["accel_topic"] = "";
  d["gyro_topic"] = "";
  return d;
}

// The log at `path`; the gyroscope from a log of its own (gyro_log) or a
// topic of its own (gyro_topic, in gyro_log or in `path`), put on the
// accelerometer's rows as `mpcal calibrate --gyro-log/--gyro-topic` does.
Recording ReadLogFrom(const std::string& path, const py::dict& options) {
  LogOptions log = LogOptionsFrom(options);
  const auto gyro_log = Get<std::string>(options, "gyro_log");
  const auto gyro_columns = Get<std::string>(options, "gyro_columns");
  const auto accel_topic = Get<std::string>(options, "accel_topic");
  const auto gyro_topic = Get<std::string>(options, "gyro_topic");
  if (!accel_topic.empty()) {
    if (!log.topic.empty()) {
      throw Error(ErrorKind::kOption,
                  "give topic (one topic with both sensors) or accel_topic and "
                  "gyro_topic (a topic per sensor), not both",
                  Suggest(Option::kLogTopic, Option::kAccelTopic));
    }
    log.topic = accel_topic;
  }
  return Interruptible([path, log, gyro_log, gyro_columns, gyro_topic] {
    Recording recording = ReadLog(path, log);
    if (gyro_log.empty() && gyro_topic.empty()) return recording;
    LogOptions gyro_options;
    gyro_options.columns = gyro_columns;
    gyro_options.time_unit = log.time_unit;
    gyro_options.rate_hz = log.rate_hz;
    gyro_options.gyro_in_dps = log.gyro_in_dps;
    gyro_options.gyro_in_counts = log.gyro_in_counts;
    gyro_options.topic = gyro_topic;
    gyro_options.recording_time = log.recording_time;
    const Recording gyro = ReadGyroLog(gyro_log.empty() ? path : gyro_log, gyro_options);
    // The gyroscope's own stream replaces whatever rates the accelerometer's
    // messages carry (a driver's accelerometer topic may fill them with zeros).
    if (!gyro_topic.empty()) recording.gyro_radps.clear();
    const StreamMerge merged = MergeGyroLog(recording, gyro, log.gyro_units());
    recording.warnings.insert(
        recording.warnings.end(), gyro.warnings.begin(), gyro.warnings.end());
    const std::string accel_name = gyro_topic.empty() ? recording.source : log.topic;
    const std::string gyro_name = gyro_topic.empty() ? gyro.source : gyro_topic;
    for (const StreamFinding f : merged.findings) {
      recording.warnings.push_back(Describe(f, merged, accel_name, gyro_name));
    }
    return recording;
  });
}

py::dict CalibrateDefaults() {
  const CalibrateOptions c;
  py::dict d;
  d["window_s"] = c.detect.window_s;
  d["min_static_s"] = c.detect.min_static_s;
  d["settle_s"] = c.detect.settle_s;
  d["threshold"] = c.detect.threshold_factor;
  d["max_still_g"] = c.detect.max_still_g;
  d["merge_gap_s"] = c.detect.merge_gap_s;
  d["merge_angle_deg"] = c.detect.merge_angle_deg;
  d["range_g"] = c.detect.range_mps2 / kStandardGravityMps2;
  d["model"] = std::string(ToString(c.solve.model));
  d["robust"] = std::string(ToString(c.solve.robust));
  d["counts_per_g"] = c.counts_per_g;
  d["gyro_window_s"] = c.gyro.direction_window_s;
  d["gyro_g_sensitivity"] = std::string(ToString(c.gyro.g_sensitivity));
  d["calibrate_gyroscope"] = c.calibrate_gyroscope;
  d["latitude_deg"] = py::none();
  d["height_m"] = 0.0;
  return d;
}

// The options of `calibrate`, as mpcal/__init__.py completed them with the
// defaults above.
CalibrateOptions CalibrateOptionsFrom(const py::dict& o, const py::object& gravity) {
  CalibrateOptions c;
  c.detect.window_s = Get<double>(o, "window_s");
  c.detect.min_static_s = Get<double>(o, "min_static_s");
  c.detect.settle_s = Get<double>(o, "settle_s");
  c.detect.threshold_factor = Get<double>(o, "threshold");
  c.detect.max_still_g = Get<double>(o, "max_still_g");
  c.detect.merge_gap_s = Get<double>(o, "merge_gap_s");
  c.detect.merge_angle_deg = Get<double>(o, "merge_angle_deg");
  c.detect.range_mps2 = Get<double>(o, "range_g") * kStandardGravityMps2;
  const auto model = ParseModelKind(Get<std::string>(o, "model"));
  const auto robust = ParseRobustLoss(Get<std::string>(o, "robust"));
  if (!model || !robust) {
    throw Error(ErrorKind::kOption,
                !model ? fmt::format("model='{}' is not a model: give 'shin-el-sheimy-9' "
                                     "or 'bias-scale-6'",
                                     Get<std::string>(o, "model"))
                       : fmt::format("robust='{}' is not a loss: give 'none', 'huber' or "
                                     "'cauchy'",
                                     Get<std::string>(o, "robust")),
                Suggest(!model ? Option::kModel : Option::kRobust));
  }
  c.solve.model = *model;
  c.solve.robust = *robust;
  c.counts_per_g = Get<double>(o, "counts_per_g");
  c.gyro.direction_window_s = Get<double>(o, "gyro_window_s");
  const auto g_mode = Get<std::string>(o, "gyro_g_sensitivity");
  if (g_mode == "auto") {
    c.gyro.g_sensitivity = GSensitivity::kAuto;
  } else if (g_mode == "on") {
    c.gyro.g_sensitivity = GSensitivity::kOn;
  } else if (g_mode == "off") {
    c.gyro.g_sensitivity = GSensitivity::kOff;
  } else {
    throw Error(
        ErrorKind::kOption,
        fmt::format("gyro_g_sensitivity='{}': give 'auto', 'on' or 'off'", g_mode));
  }
  c.calibrate_gyroscope = Get<bool>(o, "calibrate_gyroscope");
  const py::object latitude = o["latitude_deg"];
  if (!gravity.is_none() && !latitude.is_none()) {
    throw Error(ErrorKind::kOption,
                "give gravity or latitude_deg (with height_m), not both",
                Suggest(Option::kGravity, Option::kLatitude));
  }
  if (!gravity.is_none()) {
    c.solve.gravity_mps2 = gravity.cast<double>();
  } else if (!latitude.is_none()) {
    c.solve.gravity_mps2 =
        NormalGravityMps2(latitude.cast<double>(), Get<double>(o, "height_m"));
  }
  if (const std::string bad = c.Validate(); !bad.empty()) {
    throw Error(ErrorKind::kOption, "calibrate: " + bad);
  }
  return c;
}

// (calibration, findings) of `rows`, which `owner` keeps alive (a Recording,
// or the rows converted from the caller's arrays) together with `in_use`
// (the caller's arrays the rows view in place).
py::tuple CalibrateRows(const RecordingView& rows,
                        std::shared_ptr<const void> owner,
                        py::object in_use,
                        const py::object& gravity,
                        const py::dict& options,
                        const std::string& provenance) {
  const CalibrateOptions c = CalibrateOptionsFrom(options, gravity);
  if (c.counts_per_g > 0.0 && rows.units != AccelUnits::kCounts) {
    throw Error(ErrorKind::kOption,
                "counts_per_g is the scale of raw counts: it goes with units='counts'",
                Suggest(Option::kLogUnits, "counts"));
  }
  CalibrateResult result = Interruptible(
      [rows, owner = std::move(owner), c] { return CalibrateRecording(rows, c); },
      std::move(in_use));
  if (!result.solve.converged()) {
    throw Error(ErrorKind::kSession,
                fmt::format("the fit did not converge ({}); check the positions with "
                            "mpcal.detect",
                            result.solve.message),
                Advice{{}, Stage::kDetect, ""});
  }
  result.calibration.provenance = Provenance{MPCAL_VERSION, "<arrays>", provenance};
  py::list findings = CalibrateFindings(result);
  return py::make_tuple(py::cast(std::move(result.calibration)), findings);
}

// Arrays of the caller's, read where they are (float64 in C order, as
// mpcal/__init__.py hands them over). A NaN or an infinity in them the
// library refuses as it first reads the rows (NotFiniteError: the argument
// and the row; mpcal/__init__.py words the error).
py::tuple Calibrate(const Rows& t,
                    const Rows& accel,
                    const py::object& gyro,
                    const std::string& units,
                    const std::string& gyro_units,
                    const py::object& gravity,
                    const py::dict& options,
                    const std::string& provenance) {
  CalibrateOptionsFrom(options, gravity);  // bad options before the rows
  std::optional<Rows> gyro_rows;
  if (!gyro.is_none()) gyro_rows = gyro.cast<Rows>();
  std::shared_ptr<const ArraysView> arrays =
      ViewArrays(t, accel, gyro_rows, gyro, units, gyro_units);
  const RecordingView rows = arrays->rows;
  py::object in_use =
      gyro_rows ? py::make_tuple(t, accel, *gyro_rows) : py::make_tuple(t, accel);
  return CalibrateRows(
      rows, std::move(arrays), std::move(in_use), gravity, options, provenance);
}

// accel (N×3, the calibration's input units) corrected into `out` (N×3 m/s²);
// gyro too when given, into `gyro_out` (rad/s).
py::tuple Correct(const Calibration& calibration,
                  const Rows& accel,
                  const py::object& gyro,
                  const std::string& units,
                  const std::string& gyro_units) {
  const AccelUnits log_units = AccelUnitsArgument(units, "units");
  const Corrector corrector(calibration, log_units, AccelUnits::kMps2);
  std::optional<GyroCorrector> gyro_corrector;
  std::optional<Rows> gyro_rows;
  if (!gyro.is_none()) {
    if (!calibration.gyroscope) {
      throw Error(ErrorKind::kInput,
                  "gyro: the calibration has no gyroscope (made from a recording without "
                  "one); calibrate a recording with gyroscope readings");
    }
    gyro_corrector.emplace(*calibration.gyroscope,
                           GyroUnitsArgument(gyro_units, "gyro_units"),
                           GyroUnits::kRadps);
    gyro_rows = gyro.cast<Rows>();
  }
  const auto n = accel.shape(0);
  Rows out({n, py::ssize_t{3}});
  std::optional<Rows> gyro_out;
  if (gyro_rows) gyro_out.emplace(std::vector<py::ssize_t>{n, 3});
  using Block =
      Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>;
  using OutBlock = Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>;
  const Block in(accel.data(), n, 3);
  OutBlock result(out.mutable_data(), n, 3);
  {
    const py::gil_scoped_release unlocked;
    for (py::ssize_t i = 0; i < n; ++i) {
      result.row(i) = corrector(in.row(i).transpose()).transpose();
    }
    if (gyro_rows) {
      const Block g(gyro_rows->data(), n, 3);
      OutBlock w(gyro_out->mutable_data(), n, 3);
      for (py::ssize_t i = 0; i < n; ++i) {
        w.row(i) = (*gyro_corrector)(g.row(i).transpose(), result.row(i).transpose())
                       .transpose();
      }
    }
  }
  if (gyro_out) return py::make_tuple(out, *gyro_out);
  return py::make_tuple(out, py::none());
}

}  // namespace

PYBIND11_MODULE(_mpcal, m) {
  m.doc() = "mpcal's library on numpy arrays (the package mpcal wraps it).";
  m.attr("__version__") = MPCAL_VERSION;
  RegisterErrorTranslator();

  // Held by a shared pointer: a call that Ctrl-C interrupted may still be
  // reading the rows on its own thread.
  py::class_<Recording, std::shared_ptr<Recording>>(
      m,
      "Recording",
      "A log in memory (mpcal.read_log, mpcal.simulate_static): read-only numpy views "
      "of the rows the library holds, no copy.")
      .def_property_readonly(
          "t",
          [](const py::object& self) {
            const auto& r = self.cast<const Recording&>();
            return ViewOf(r.time_s.data(), r.size(), 1, self);
          },
          "Time of each row (s, N), the log's own clock, strictly increasing.")
      .def_property_readonly(
          "accel",
          [](const py::object& self) {
            const auto& r = self.cast<const Recording&>();
            return ViewOf(r.accel.empty() ? nullptr : r.accel.front().data(),
                          r.accel.size(),
                          3,
                          self);
          },
          "Accelerometer readings (N×3: x, y, z) in `units`.")
      .def_property_readonly(
          "gyro",
          [](const py::object& self) -> py::object {
            const auto& r = self.cast<const Recording&>();
            if (r.gyro_radps.empty()) return py::none();
            return ViewOf(r.gyro_radps.front().data(), r.gyro_radps.size(), 3, self);
          },
          "Gyroscope readings (N×3) in rad/s (a log in deg/s converted on reading), or "
          "raw counts when `gyro_units` is 'counts'; None without a gyroscope.")
      .def_property_readonly(
          "units",
          [](const Recording& r) { return std::string(ToString(r.units)); },
          "Units of `accel`: 'mps2', 'g' or 'counts'.")
      .def_property_readonly(
          "gyro_units",
          [](const Recording& r) { return std::string(ToString(r.gyro_units)); },
          "Units of `gyro`: 'rads' or 'counts'.")
      .def_readonly("source", &Recording::source, "Where the rows came from (a path).")
      .def_readonly(
          "warnings",
          &Recording::warnings,
          "The reader's findings: gaps, duplicated times, a truncated last line.")
      .def("__len__", &Recording::size, "Rows.");

  py::class_<Calibration>(m, "Calibration")
      .def("_json", &CalibrationToJson)
      .def("_save",
           [](const Calibration& c, const std::string& path) {
             CheckWritable(path);
             WriteCalibrationFile(path, c);
           })
      .def("_correct", &Correct);

  m.def("_read_log", &ReadLogFrom);
  m.def("_read_log_defaults", &ReadLogDefaults);
  m.def("_calibrate", &Calibrate);
  // The rows of a Recording as they are (its own arrays): no copy.
  m.def("_calibrate_recording",
        [](std::shared_ptr<Recording> recording,
           const py::object& gravity,
           const py::dict& options,
           const std::string& provenance) {
          const RecordingView rows = *recording;
          return CalibrateRows(
              rows, std::move(recording), py::none(), gravity, options, provenance);
        });
  m.def("_calibrate_defaults", &CalibrateDefaults);
  m.def("_load_calibration", [](const std::string& path) {
    const py::gil_scoped_release unlocked;
    return ReadCalibrationFile(path);
  });
  AddDetect(m);
  AddSimulate(m);
  AddNoise(m);
  AddExport(m);
}

}  // namespace mpcal::python
