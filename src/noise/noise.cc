// A recording's noise: which samples, the sample period, and the
// accelerometer and gyroscope analysed side by side on two threads.
#include <algorithm>
#include <cmath>
#include <exception>
#include <string>
#include <thread>
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

// The typical spacing: the median of up to 100,000 spacings spread over the
// segment (a copy of all of them would cost as much memory as the time).
double MedianPeriod(const std::vector<double>& t, std::size_t begin, std::size_t end) {
  const std::size_t n = end - begin - 1;
  const std::size_t step = std::max<std::size_t>(1, n / 100000);
  std::vector<double> dt;
  for (std::size_t i = begin; i + 1 < end; i += step) dt.push_back(t[i + 1] - t[i]);
  std::nth_element(dt.begin(), dt.begin() + dt.size() / 2, dt.end());
  return dt[dt.size() / 2];
}

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

SensorNoise AnalyseSensorNoise(const CumulativeSums3& sums, const NoiseOptions& options) {
  if (const std::string bad = options.Validate(); !bad.empty()) {
    throw Error(ErrorKind::kOption, "noise options: " + bad);
  }
  std::array<std::vector<AllanPoint>, 3> curves = OverlappingAllan(sums, options.allan);
  SensorNoise out;
  out.mean_si = sums.mean_si();
  for (int axis = 0; axis < 3; ++axis) {
    out.axes[axis] = internal::AnalyseAxis(
        std::move(curves[axis]), static_cast<double>(sums.size()), options);
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

NoiseResult AnalyseNoise(Recording&& recording,
                         const NoiseSegment& segment,
                         double accel_mps2_per_unit,
                         const NoiseOptions& options) {
  if (const std::string bad = options.Validate(); !bad.empty()) {
    throw Error(ErrorKind::kOption, "noise options: " + bad);
  }
  if (segment.end > recording.size() || segment.begin + 9 > segment.end) {
    throw Error(
        ErrorKind::kInput,
        fmt::format("{}: {} samples are too few for an Allan deviation (at least 9)",
                    recording.source,
                    segment.end > segment.begin ? segment.end - segment.begin : 0));
  }
  NoiseResult r;
  r.segment = segment;
  r.sample_period_s = MedianPeriod(recording.time_s, segment.begin, segment.end);
  if (!(r.sample_period_s > 0.0))
    throw Error(ErrorKind::kTime, recording.source + ": no sample spacing");
  r.rate_hz = 1.0 / r.sample_period_s;
  for (std::size_t i = segment.begin + 1; i < segment.end; ++i) {
    if (recording.time_s[i] - recording.time_s[i - 1] > 1.5 * r.sample_period_s) ++r.gaps;
  }
  r.samples = segment.end - segment.begin;
  r.record_s = static_cast<double>(r.samples) * r.sample_period_s;
  const bool has_gyro = recording.gyro_radps.size() == recording.size();
  std::vector<double>().swap(recording.time_s);

  std::exception_ptr gyro_error;
  std::optional<SensorNoise> gyro;
  std::thread gyro_thread;
  if (has_gyro) {
    gyro_thread = std::thread([&] {
      try {
        const CumulativeSums3 sums =
            CumulativeSums3::FromSamples(std::move(recording.gyro_radps),
                                         segment.begin,
                                         segment.end,
                                         1.0,
                                         r.sample_period_s);
        gyro = AnalyseSensorNoise(sums, options);
      } catch (...) {
        gyro_error = std::current_exception();
      }
    });
  }
  std::exception_ptr accel_error;
  try {
    const CumulativeSums3 sums = CumulativeSums3::FromSamples(std::move(recording.accel),
                                                              segment.begin,
                                                              segment.end,
                                                              accel_mps2_per_unit,
                                                              r.sample_period_s);
    r.accel_mps2 = AnalyseSensorNoise(sums, options);
  } catch (...) {
    accel_error = std::current_exception();
  }
  if (gyro_thread.joinable()) gyro_thread.join();
  if (accel_error) std::rethrow_exception(accel_error);
  if (gyro_error) std::rethrow_exception(gyro_error);
  r.gyro_radps = std::move(gyro);
  return r;
}

}  // namespace mpcal
