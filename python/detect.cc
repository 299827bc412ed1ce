// mpcal.detect on arrays: the static positions, the coverage of the sphere
// and the findings, as plain Python data (the package wraps them).
#include "detect.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "arrays.h"
#include "errors.h"
#include "mpcal/calibrate.h"
#include "mpcal/coverage.h"
#include "mpcal/detect.h"

namespace mpcal::python {
namespace {

py::list Vec(const Eigen::Vector3d& v) {
  return py::cast(std::vector<double>{v.x(), v.y(), v.z()});
}

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

py::dict Finding(std::string kind, const std::string& sentence, const Advice& advice) {
  py::dict d;
  d["kind"] = std::move(kind);
  d["message"] = sentence;
  d["advice"] = AdviceSettings(advice);
  d["stage"] = StageOf(advice);
  return d;
}

py::dict CoverageDict(const CoverageResult& c) {
  const auto& names = CanonicalDirections();
  auto down = [&](const std::vector<int>& indices) {
    py::list out;
    for (int i : indices) out.append(names[static_cast<std::size_t>(i)].down);
    return out;
  };
  py::dict d;
  d["positions"] = c.positions;
  d["distinct_positions"] = c.distinct_positions;
  d["required_positions"] = c.required_positions;
  d["recommended_positions"] = c.recommended_positions;
  d["covered"] = down(c.covered);
  d["missing"] = down(c.missing);
  d["verdict"] = std::string(ToString(c.verdict));
  d["observability"] = c.observability;
  d["largest_empty_cap_deg"] = c.largest_empty_cap_deg;
  d["emptiest_direction"] = Vec(c.emptiest_direction);
  d["summary"] = Summary(c);
  py::list problems;
  for (const CoverageProblem& p : c.problems) problems.append(Describe(p));
  d["problems"] = problems;
  py::list steps;
  for (const CoverageStep& s : c.advice) {
    steps.append(Finding("coverage_step", Describe(s), s.advice));
  }
  d["next_steps"] = steps;
  return d;
}

py::dict Detect(const Rows& t,
                const Rows& accel,
                const std::string& units,
                double gravity_mps2,
                const py::dict& o) {
  Recording recording = ToRecording(t, accel, py::none(), units, "rads");
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
  coverage_options.units = recording.units;
  // The hold a new position needs, as `mpcal detect` advises it.
  coverage_options.hold_s = std::max(
      10.0, std::ceil(options.min_static_s + 2 * options.settle_s + options.window_s));
  DetectResult detection;
  CoverageResult coverage;
  {
    const py::gil_scoped_release unlocked;
    CheckUnits(recording, gravity_mps2);
    detection = DetectStatic(recording, options);
    coverage = AssessCoverage(detection, coverage_options);
  }
  py::list positions;
  for (const StaticInterval& s : detection.intervals) {
    py::dict p;
    p["begin"] = s.begin;
    p["end"] = s.end;
    p["start_s"] = s.start_s;
    p["end_s"] = s.end_s;
    p["samples"] = s.samples();
    p["mean"] = Vec(s.mean);
    p["std"] = Vec(s.std);
    positions.append(p);
  }
  py::dict d;
  d["positions"] = positions;
  d["coverage"] = CoverageDict(coverage);
  d["quiet_level"] = detection.quiet_level;
  d["threshold"] = detection.threshold;
  d["threshold_capped"] = detection.threshold_capped;
  d["still_fraction"] = detection.still_fraction;
  d["longest_still_s"] = detection.longest_still_s;
  d["sample_period_s"] = detection.sample_period_s;
  d["dropped_short"] = detection.dropped_short;
  d["dropped_clipped"] = detection.dropped_clipped;
  d["merged"] = detection.merged;
  d["outcome"] = Finding(OutcomeName(detection.finding.kind),
                         Describe(detection.finding),
                         detection.finding.advice);
  py::list notes;
  for (const DetectNote& n : detection.notes) {
    notes.append(Finding(
        n.kind == DetectNoteKind::kClippedPosition ? "clipped_position" : "not_still",
        Describe(n),
        n.advice));
  }
  d["findings"] = notes;
  return d;
}

}  // namespace

void AddDetect(py::module_& m) { m.def("_detect", &Detect); }

}  // namespace mpcal::python
