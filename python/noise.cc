// mpcal.noise on arrays: the Allan deviation and the noise terms of a still
// record, as `mpcal noise --json` writes them.
#include "noise.h"

#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "arrays.h"
#include "errors.h"
#include "interrupt.h"
#include "mpcal/calibrate.h"
#include "mpcal/detect.h"
#include "mpcal/error.h"
#include "mpcal/noise.h"
#include "mpcal/noise_file.h"

namespace mpcal::python {
namespace {

DetectOptions DetectOptionsFrom(const py::dict& o) {
  DetectOptions d;
  d.window_s = o["window_s"].cast<double>();
  d.min_static_s = o["min_static_s"].cast<double>();
  d.settle_s = o["settle_s"].cast<double>();
  d.threshold_factor = o["threshold"].cast<double>();
  d.max_still_g = o["max_still_g"].cast<double>();
  d.merge_gap_s = o["merge_gap_s"].cast<double>();
  d.merge_angle_deg = o["merge_angle_deg"].cast<double>();
  d.range_mps2 = o["range_g"].cast<double>() * kStandardGravityMps2;
  if (const std::string bad = d.Validate(); !bad.empty()) {
    throw Error(ErrorKind::kOption, "noise: " + bad);
  }
  return d;
}

// The part `mpcal noise` analyses: the whole record when the sensor never
// moved (or `whole`), else detection's longest still part.
NoiseResult Analyse(const RecordingView& rows,
                    const NoiseOptions& options,
                    const DetectOptions& detect,
                    bool whole,
                    double mps2_per_unit) {
  NoiseStream stream(options, whole ? nullptr : &detect, rows.units);
  stream.Add(rows);
  const std::optional<StillVerdict> still = stream.Stillness();
  if (!still || still->still) {
    const NoiseSegment all{NoiseSegmentKind::kWholeRecord, 0, stream.rows(), 1};
    return stream.Finish(mps2_per_unit, all);
  }
  const DetectResult detection = DetectStatic(rows, detect);
  const std::optional<NoiseSegment> segment = ChooseNoiseSegment(rows, detection);
  if (!segment) {
    throw Error(ErrorKind::kSession,
                "no still part found (" + DescribeFacts(detection.finding) +
                    "); if the sensor was still, give whole=True to analyse all of it",
                detection.finding.advice);
  }
  return AnalyseNoise(rows, *segment, mps2_per_unit, options);
}

py::dict Noise(const Rows& t,
               const Rows& accel,
               const py::object& gyro,
               const std::string& units,
               const std::string& gyro_units,
               double gravity_mps2,
               bool whole,
               double confidence,
               const py::dict& detect_options) {
  const DetectOptions detect = DetectOptionsFrom(detect_options);
  NoiseOptions options;
  options.allan.confidence = confidence;
  if (const std::string bad = options.Validate(); !bad.empty()) {
    throw Error(ErrorKind::kOption, "noise: " + bad);
  }
  // Read in place, as calibrate reads them (a gyroscope in deg/s converted).
  std::optional<Rows> gyro_rows;
  if (!gyro.is_none()) gyro_rows = gyro.cast<Rows>();
  std::shared_ptr<const ArraysView> arrays =
      ViewArrays(t, accel, gyro_rows, gyro, units, gyro_units);
  const RecordingView rows = arrays->rows;
  const std::optional<double> mps2_per_unit = FixedMps2PerUnit(rows.units);
  if (!mps2_per_unit || rows.gyro_units == GyroUnits::kCounts) {
    throw Error(ErrorKind::kUnits,
                "the noise of raw counts has no unit: give readings in m/s² or g (and "
                "rad/s or deg/s), e.g. corrected by a calibration made in counts "
                "(Calibration.correct)",
                Suggest(Option::kLogUnits));
  }
  py::object in_use =
      gyro_rows ? py::make_tuple(t, accel, *gyro_rows) : py::make_tuple(t, accel);
  const NoiseResult result = Interruptible(
      [rows,
       arrays = std::move(arrays),
       options,
       detect,
       whole,
       gravity_mps2,
       k = *mps2_per_unit] {
        CheckUnits(rows, gravity_mps2);
        return Analyse(rows, options, detect, whole, k);
      },
      std::move(in_use));
  return py::module_::import("json").attr("loads")(
      NoiseJson(result, "<arrays>", confidence));
}

py::dict NoiseDefaults() {
  const NoiseOptions options;
  py::dict d;
  d["whole"] = false;
  d["confidence"] = options.allan.confidence;
  return d;
}

}  // namespace

void AddNoise(py::module_& m) {
  m.def("_noise", &Noise);
  m.def("_noise_defaults", &NoiseDefaults);
}

}  // namespace mpcal::python
