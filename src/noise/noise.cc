// A recording's noise: which samples, and each sensor's curves and terms.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "mpcal/error.h"
#include "mpcal/noise.h"
#include "noise/noise_fit.h"

namespace mpcal {

namespace {

// A still stretch this close to the whole record is the whole record: the
// detector trims a settle time at each end even when nothing moved.
constexpr double kWholeRecordFraction = 0.98;

}  // namespace

std::string_view ToString(NoiseSegmentKind kind) {
  switch (kind) {
    case NoiseSegmentKind::kWholeRecord:
      return "whole_record";
    case NoiseSegmentKind::kLongestStill:
      return "longest_still";
  }
  return "?";
}

SensorNoise AnalyseSensorNoise(const AllanSums& sums,
                               double si_per_unit,
                               double sample_period_s,
                               const NoiseOptions& options) {
  if (const std::string bad = options.Validate(); !bad.empty()) {
    throw Error(ErrorKind::kOption, "noise options: " + bad);
  }
  std::array<std::vector<AllanPoint>, 3> curves =
      sums.Curves(si_per_unit, sample_period_s);
  SensorNoise out;
  out.mean_si = sums.Mean() * si_per_unit;
  for (int axis = 0; axis < 3; ++axis) {
    out.axes[axis] = internal::AnalyseAxis(
        std::move(curves[axis]), static_cast<double>(sums.samples() + 1), options);
  }
  return out;
}

std::optional<NoiseSegment> ChooseNoiseSegment(const Recording& recording,
                                               const DetectResult& detection) {
  if (detection.intervals.empty()) return std::nullopt;
  NoiseSegment s;
  s.static_intervals = detection.intervals.size();
  const auto longest =
      std::max_element(detection.intervals.begin(),
                       detection.intervals.end(),
                       [](const StaticInterval& a, const StaticInterval& b) {
                         return a.end - a.begin < b.end - b.begin;
                       });
  const double covered = static_cast<double>(longest->end - longest->begin) /
                         static_cast<double>(std::max<std::size_t>(recording.size(), 1));
  if (detection.intervals.size() == 1 && covered >= kWholeRecordFraction) {
    s.kind = NoiseSegmentKind::kWholeRecord;
    s.begin = 0;
    s.end = recording.size();
  } else {
    s.kind = NoiseSegmentKind::kLongestStill;
    s.begin = longest->begin;
    s.end = longest->end;
  }
  return s;
}

std::optional<Eigen::Vector3d> WhiteNoiseFromPositions(
    const std::vector<PositionSummary>& positions) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double dof = 0.0;
  for (const PositionSummary& p : positions) {
    if (p.samples < 2 || !(p.end_s > p.start_s)) continue;
    // Samples n over [start, end] are n − 1 periods apart.
    const double rate_hz = static_cast<double>(p.samples - 1) / (p.end_s - p.start_s);
    const double w = static_cast<double>(p.samples - 1);
    sum += w * p.sample_std_mps2.cwiseAbs2() / rate_hz;
    dof += w;
  }
  if (dof <= 0.0) return std::nullopt;
  return (sum / dof).cwiseSqrt();
}

}  // namespace mpcal
