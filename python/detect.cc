// mpcal.detect on arrays: the static positions, the coverage of the sphere
// and the findings, as plain Python data (the package wraps them).
#include "detect.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <utility>

#include "arrays.h"
#include "errors.h"
#include "findings.h"
#include "interrupt.h"
#include "mpcal/calibrate.h"
#include "mpcal/coverage.h"
#include "mpcal/detect.h"

namespace mpcal::python {
namespace {

std::string OutcomeName(DetectOutcome kind) {
  switch (kind) {
    case DetectOutcome::kFound:
      return "found";
    case DetectOutcome::kNeverStill:
      return "never_still";
    case DetectOutcome::kTooShort:
      return "too_short";
    case DetectOutcome::kAllClipped:
      return "all_clipped";
  }
  return "found";
}

py::dict Detect(const Rows& t,
                const Rows& accel,
                const std::string& units,
                double gravity_mps2,
                const py::dict& o) {
  // Read in place, as calibrate reads them.
  std::shared_ptr<const ArraysView> arrays =
      ViewArrays(t, accel, std::nullopt, py::none(), units, "rads");
  const RecordingView rows = arrays->rows;
  DetectOptions options;
  options.window_s = o["window_s"].cast<double>();
  options.min_static_s = o["min_static_s"].cast<double>();
  options.settle_s = o["settle_s"].cast<double>();
  options.threshold_factor = o["threshold"].cast<double>();
  options.max_still_g = o["max_still_g"].cast<double>();
  options.merge_gap_s = o["merge_gap_s"].cast<double>();
  options.merge_angle_deg = o["merge_angle_deg"].cast<double>();
  options.range_mps2 = o["range_g"].cast<double>() * kStandardGravityMps2;
  if (const std::string bad = options.Validate(); !bad.empty()) {
    throw Error(ErrorKind::kOption, "detect: " + bad);
  }
  CoverageOptions coverage_options;
  coverage_options.units = rows.units;
  // The hold a new position needs, as `mpcal detect` advises it.
  coverage_options.hold_s = std::max(
      10.0, std::ceil(options.min_static_s + 2 * options.settle_s + options.window_s));
  auto [detection, coverage] = Interruptible(
      [rows, arrays = std::move(arrays), options, coverage_options, gravity_mps2] {
        CheckUnits(rows, gravity_mps2);
        DetectResult found = DetectStatic(rows, options);
        CoverageResult covered = AssessCoverage(found, coverage_options);
        return std::pair{std::move(found), std::move(covered)};
      },
      py::make_tuple(t, accel));
  // The document `mpcal detect --json` writes (mpcal.detection/1), with
  // the outcome and the findings' advice as facts beside its sentences.
  py::dict d = py::module_::import("json").attr("loads")(DetectionReportJson(
      detection, coverage, coverage_options, "<arrays>", nullptr, {}));
  const DetectFinding& found = detection.finding;
  py::dict figures;
  figures["span_s"] = found.span_s;
  figures["longest_still_s"] = found.longest_still_s;
  figures["quiet_level"] = found.quiet_level;
  figures["quiet_g"] = found.quiet_g;
  figures["threshold"] = found.threshold;
  figures["threshold_capped"] = found.threshold_capped;
  figures["dropped_short"] = found.dropped_short;
  figures["dropped_clipped"] = found.dropped_clipped;
  d["outcome"] = FindingOf(
      OutcomeName(found.kind), Describe(found), found.advice, std::move(figures));
  py::list notes;
  for (const DetectNote& n : detection.notes) {
    notes.append(DetectNoteFinding(n, Describe(n)));
  }
  d["findings"] = notes;
  return d;
}

}  // namespace

void AddDetect(py::module_& m) { m.def("_detect", &Detect); }

}  // namespace mpcal::python
