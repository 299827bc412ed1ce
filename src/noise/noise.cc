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

void SetRecordNeeded(SensorNoise& sensor) {
  for (int t = 0; t < kNoiseTermCount; ++t) {
    sensor.record_needed_s[t].reset();
    sensor.record_needed_half_s[t].reset();
    for (const AxisNoise& a : sensor.axes) {
      const TermEstimate& e = a.terms[t];
      if (e.status != TermStatus::kNotSeen) continue;
      const auto longest = [](std::optional<double>& to, std::optional<double> v) {
        if (v && (!to || *v > *to)) to = v;
      };
      longest(sensor.record_needed_s[t], e.record_needed_s);
      longest(sensor.record_needed_half_s[t], e.record_needed_half_s);
    }
  }
}

std::string FormatRecordLength(double seconds) {
  if (seconds >= 3600.0) return fmt::format("{:.1f} h", seconds / 3600.0);
  if (seconds >= 60.0) return fmt::format("{:.0f} min", seconds / 60.0);
  return fmt::format("{:.0f} s", seconds);
}

std::string FormatTauRanges(const std::vector<TauRange>& ranges, int max_ranges) {
  std::vector<TauRange> shown = ranges;
  const auto span = [](const TauRange& r) { return r.hi_s / r.lo_s; };
  std::stable_sort(shown.begin(), shown.end(), [&](const TauRange& a, const TauRange& b) {
    return span(a) > span(b);
  });
  const std::size_t keep =
      std::min(shown.size(), static_cast<std::size_t>(std::max(max_ranges, 0)));
  const std::size_t more = shown.size() - keep;
  shown.resize(keep);
  std::sort(shown.begin(), shown.end(), [](const TauRange& a, const TauRange& b) {
    return a.lo_s < b.lo_s;
  });
  std::string out;
  for (const TauRange& r : shown) {
    if (!out.empty()) out += ", ";
    out += r.lo_s == r.hi_s ? fmt::format("{:.2g} s", r.lo_s)
                            : fmt::format("{:.2g}\u2013{:.2g} s", r.lo_s, r.hi_s);
  }
  if (more > 0) out += fmt::format(" + {} more", more);
  return out;
}

std::string_view ToString(SignalFault fault) {
  switch (fault) {
    case SignalFault::kStuck:
      return "stuck";
    case SignalFault::kTwoValued:
      return "two_valued";
    case SignalFault::kBelowResolution:
      return "below_resolution";
  }
  return "?";
}

std::vector<AxisSignalFault> SignalFaults(const AllanSums& sums,
                                          double si_per_unit,
                                          bool gyroscope) {
  std::vector<AxisSignalFault> out;
  if (sums.samples() < 2) return out;
  for (int axis = 0; axis < 3; ++axis) {
    const AllanSums::AxisValues v = sums.Values(axis);
    AxisSignalFault f;
    f.gyroscope = gyroscope;
    f.axis = axis;
    f.value_si = v.first * si_per_unit;
    f.resolution_si = v.resolution * si_per_unit;
    f.adev_tau0_si = v.adev_tau0 * si_per_unit;
    // White noise of σ per sample has an Allan deviation of σ at τ0; a
    // quantiser of step q adds q/√12 and follows the noise only while σ is
    // about q or more (Widrow & Kollár 2008, ch. 4): below, what varies is
    // the quantiser's rounding.
    if (v.distinct == 1) {
      f.fault = SignalFault::kStuck;
    } else if (v.distinct == 2) {
      f.fault = SignalFault::kTwoValued;
    } else if (v.adev_tau0 < v.resolution) {
      f.fault = SignalFault::kBelowResolution;
    } else {
      continue;
    }
    out.push_back(f);
  }
  return out;
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
  SetRecordNeeded(out);
  return out;
}

std::optional<NoiseSegment> ChooseNoiseSegment(const RecordingView& recording,
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
