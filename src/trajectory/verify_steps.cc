// The steps of Verify (verify_steps.h): inputs, start of motion, clocks,
// the reference over the overlap, the heading epoch, findings about the walk.
#include "trajectory/verify_steps.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <fmt/format.h>

#include "mpcal/count.h"
#include "mpcal/error.h"
#include "mpcal/units.h"

namespace mpcal::internal {
namespace {

// Window after the start of motion over which the clocks are matched (s), and
// the search range around the first guess (s).
constexpr double kRefineWindowS = 5.0;
constexpr double kRefineRangeS = 1.5;
constexpr double kRefineStepS = 0.005;
// Walking is motion that lasts at least this long (s).
constexpr double kSustainedMotionS = 3.0;
// GPS time minus UTC (s): a disagreement of about this is a time system mix-up.
constexpr double kGpsMinusUtcS = 18.0;

double HorizontalDistance(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::hypot(a.x() - b.x(), a.y() - b.y());
}

// Advice to set any one of `settings`.
Advice GiveOneOf(std::vector<Setting> settings) {
  Advice advice;
  advice.settings = std::move(settings);
  return advice;
}

VerifyFinding Finding(VerifyFindingKind kind, std::string what) {
  VerifyFinding finding;
  finding.kind = kind;
  finding.what = std::move(what);
  return finding;
}

std::string Span(double a, double b) { return fmt::format("{:.3f} .. {:.3f} s", a, b); }

// The level of the motion statistic that counts as walking: a quarter of its
// median over the moving samples, and at least the still threshold.
std::optional<double> WalkingLevel(const StillResult& still) {
  std::vector<double> moving;
  for (std::size_t i = 0; i < still.still.size(); ++i) {
    if (!still.still[i]) moving.push_back(still.accel_std_mps2[i]);
  }
  if (moving.empty()) return std::nullopt;
  const auto mid = moving.begin() + static_cast<std::ptrdiff_t>(moving.size() / 2);
  std::nth_element(moving.begin(), mid, moving.end());
  return std::max(0.25 * *mid, still.accel_threshold_mps2);
}

void ThrowIfNoMotionStart(const MotionStartMissing& missing) {
  throw Error(
      ErrorKind::kTime,
      fmt::format("cannot align the clocks by the start of motion: {}",
                  missing.imu_has_no_rest
                      ? fmt::format("{} does not start at rest", missing.imu_source)
                      : fmt::format("{} never moves {} m from its first position",
                                    missing.reference_source,
                                    kDepartureM)),
      GiveOneOf({{Option::kTimeOffset, ""}}));
}

VerifyFinding ClockDisagreement(double motion_offset_s) {
  VerifyFinding finding;
  finding.kind = VerifyFindingKind::kClockDisagreement;
  finding.motion_offset_s = motion_offset_s;
  finding.what = fmt::format(
      "on the common clock the start of motion differs by {:.2f} s between the IMU log "
      "and the reference{}",
      motion_offset_s,
      std::abs(std::abs(motion_offset_s) - kGpsMinusUtcS) < 1.0
          ? " (18 s is GPS time minus UTC)"
          : "");
  finding.advice.settings = {{Option::kTimeAlign, "motion"}, {Option::kTimeOffset, ""}};
  return finding;
}

}  // namespace

double CheckVerifyInputs(const Recording& imu,
                         const GnssTrack& reference,
                         const std::optional<Calibration>& calibration,
                         const VerifyOptions& options) {
  if (const std::string p = options.Validate(); !p.empty()) {
    throw Error(ErrorKind::kOption, "verify options: " + p);
  }
  const std::size_t n = imu.size();
  if (n < 3 || imu.accel.size() != n) {
    throw Error(ErrorKind::kInput,
                fmt::format("{}: the IMU log has {}; a walk needs many more",
                            imu.source,
                            Count(n, "sample")));
  }
  if (!imu.gyro_radps.empty() && imu.gyro_radps.size() != n) {
    throw Error(ErrorKind::kInput,
                fmt::format("{}: {} gyroscope readings for {} samples",
                            imu.source,
                            imu.gyro_radps.size(),
                            n));
  }
  if (reference.size() < 2) {
    throw Error(ErrorKind::kInput,
                fmt::format("{}: the reference has {}; a walk needs many more",
                            reference.source,
                            Count(reference.size(), "epoch")));
  }
  const std::optional<double> scale = FixedMps2PerUnit(imu.units);
  if (!scale) {
    throw Error(ErrorKind::kUnits,
                fmt::format("{}: the log is in raw counts, which have no physical scale "
                            "to integrate; convert it to g or m/s2 first",
                            imu.source),
                GiveOneOf({{Option::kLogUnits, "g"}, {Option::kLogUnits, "mps2"}}));
  }
  if (calibration && calibration->input_units != imu.units) {
    throw Error(ErrorKind::kUnits,
                fmt::format("the calibration is for logs in {}, but {} is read as {}",
                            ToString(calibration->input_units),
                            imu.source,
                            ToString(imu.units)),
                GiveOneOf({{Option::kLogUnits,
                            std::string(ToString(calibration->input_units))}}));
  }
  return *scale;
}

std::optional<double> ReferenceMotionStart(const TimedPath& ref) {
  const Eigen::Vector3d r0 = ref.position_m.front();
  std::size_t k1 = 0;
  while (k1 < ref.size() && HorizontalDistance(ref.position_m[k1], r0) < kDepartureM)
    ++k1;
  if (k1 == ref.size()) return std::nullopt;
  double sum_sq = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 0; i < k1 && ref.time_s[i] < ref.time_s[0] + 2.0; ++i) {
    const double d = HorizontalDistance(ref.position_m[i], r0);
    sum_sq += d * d;
    ++count;
  }
  const double jitter = count > 0 ? std::sqrt(sum_sq / static_cast<double>(count)) : 0.0;
  const double at_rest = std::max(0.05, 3.0 * jitter);
  std::size_t k0 = k1;
  while (k0 > 0 && HorizontalDistance(ref.position_m[k0], r0) > at_rest) --k0;
  return ref.time_s[k0];
}

// Picking the device up before setting off is shorter than kSustainedMotionS,
// and is not taken for the start.
std::optional<std::size_t> ImuMotionStart(const StillResult& still,
                                          std::span<const double> time_s) {
  const std::size_t n = still.still.size();
  if (still.initial_rest_end == 0 || still.initial_rest_end >= n) return std::nullopt;
  const std::optional<double> walking = WalkingLevel(still);
  if (!walking) return std::nullopt;
  // Prefix counts of samples at the walking level.
  std::vector<std::size_t> above(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    above[i + 1] = above[i] + (still.accel_std_mps2[i] >= *walking ? 1 : 0);
  }
  std::size_t j = still.initial_rest_end;
  for (std::size_t i = still.initial_rest_end; i < n; ++i) {
    if (still.accel_std_mps2[i] < *walking) continue;
    while (j < n && time_s[j] < time_s[i] + kSustainedMotionS) ++j;
    if (j == n) break;
    if (static_cast<double>(above[j] - above[i]) >= 0.8 * static_cast<double>(j - i))
      return i;
  }
  return std::nullopt;
}

// Matches the distance from the start, which does not depend on heading.
double RefineOffset(double offset_s,
                    const TimedPath& imu_path,
                    double imu_motion_start_s,
                    const TimedPath& ref) {
  const Eigen::Vector3d r0 = ref.position_m.front();
  const Eigen::Vector3d p0 = imu_path.At(imu_motion_start_s);
  const double ref_start = imu_motion_start_s + offset_s;
  std::vector<std::size_t> epochs;
  for (std::size_t i = 0; i < ref.size(); ++i) {
    if (ref.time_s[i] >= ref_start - 1.0 && ref.time_s[i] <= ref_start + kRefineWindowS) {
      epochs.push_back(i);
    }
  }
  if (epochs.size() < 5) return offset_s;
  double best = offset_s;
  double best_cost = std::numeric_limits<double>::infinity();
  for (double o = offset_s - kRefineRangeS; o <= offset_s + kRefineRangeS;
       o += kRefineStepS) {
    double cost = 0.0;
    for (const std::size_t i : epochs) {
      const double d_ref = HorizontalDistance(ref.position_m[i], r0);
      const double d_imu = HorizontalDistance(imu_path.At(ref.time_s[i] - o), p0);
      cost += (d_ref - d_imu) * (d_ref - d_imu);
    }
    if (cost < best_cost) {
      best_cost = cost;
      best = o;
    }
  }
  return best;
}

TimeAlignMode ResolveAlignMode(TimeAlignMode requested,
                               const ClockSpans& spans,
                               bool has_motion_offset) {
  if (requested != TimeAlignMode::kAuto) return requested;
  const double common_overlap = std::min(spans.imu_end_s, spans.ref_end_s) -
                                std::max(spans.imu_begin_s, spans.ref_begin_s);
  const double shorter =
      std::min(spans.imu_end_s - spans.imu_begin_s, spans.ref_end_s - spans.ref_begin_s);
  return common_overlap >= 0.5 * shorter || !has_motion_offset
             ? TimeAlignMode::kCommonClock
             : TimeAlignMode::kMotionStart;
}

void AlignClocks(const ClockSpans& spans,
                 const VerifyOptions& options,
                 const MotionStartMissing& missing,
                 TimeAlignment& time,
                 std::vector<VerifyFinding>& findings) {
  time.method =
      ResolveAlignMode(options.time_align, spans, time.motion_offset_s.has_value());
  switch (time.method) {
    case TimeAlignMode::kCommonClock:
    case TimeAlignMode::kAuto:
      time.offset_s = 0.0;
      if (time.motion_offset_s && std::abs(*time.motion_offset_s) > kClockDisagreementS) {
        findings.push_back(ClockDisagreement(*time.motion_offset_s));
      }
      break;
    case TimeAlignMode::kOffset:
      time.offset_s = options.time_offset_s;
      break;
    case TimeAlignMode::kMotionStart:
      if (!time.motion_offset_s) ThrowIfNoMotionStart(missing);
      time.offset_s = *time.motion_offset_s;
      break;
  }
  const double offset = time.offset_s;
  time.overlap_start_s = std::max(spans.imu_begin_s + offset, spans.ref_begin_s);
  time.overlap_end_s = std::min(spans.imu_end_s + offset, spans.ref_end_s);
  if (time.overlap_end_s - time.overlap_start_s < options.min_overlap_s) {
    throw Error(
        ErrorKind::kTime,
        fmt::format("the IMU log and the reference do not overlap in time: the log "
                    "covers {} and the reference {} (reference clock, {} alignment, "
                    "offset {:.3f} s); they need at least {} s in common (GPS time is "
                    "18 s ahead of UTC)",
                    Span(spans.imu_begin_s + offset, spans.imu_end_s + offset),
                    Span(spans.ref_begin_s, spans.ref_end_s),
                    ToString(time.method),
                    offset,
                    options.min_overlap_s),
        GiveOneOf({{Option::kTimeAlign, "motion"}, {Option::kTimeOffset, ""}}));
  }
}

void CutReferenceToOverlap(const GnssTrack& reference,
                           double path_step_m,
                           VerifyResult& result) {
  for (std::size_t i = 0; i < reference.size(); ++i) {
    const double t = reference.time_s[i];
    if (t < result.time.overlap_start_s || t > result.time.overlap_end_s) continue;
    result.reference_path.time_s.push_back(t);
    result.reference_path.position_m.push_back(reference.enu_m[i]);
    result.reference_quality.push_back(reference.quality[i]);
  }
  const TimedPath& ref = result.reference_path;
  if (ref.size() < 2) {
    throw Error(
        ErrorKind::kInput,
        fmt::format("{}: fewer than two reference epochs within the IMU log's span",
                    reference.source));
  }
  result.reference.epochs = ref.size();
  result.reference.path_length_m = HorizontalPathLength(ref.position_m, path_step_m);
  result.reference.start_end_distance_m =
      HorizontalDistance(ref.position_m.back(), ref.position_m.front());
}

std::optional<double> HeadingTime(const TimedPath& ref, double distance_m) {
  for (std::size_t i = 0; i < ref.size(); ++i) {
    if (HorizontalDistance(ref.position_m[i], ref.position_m.front()) >= distance_m) {
      return ref.time_s[i];
    }
  }
  return std::nullopt;
}

void ThrowIfNeverMoves(const StillResult& still, const Recording& imu) {
  if (std::find(still.still.begin(), still.still.end(), false) != still.still.end()) {
    return;
  }
  throw Error(ErrorKind::kInput,
              fmt::format("{}: the IMU never moves: the still test finds it at rest "
                          "over all {:.1f} s of the log, so there is no walk to "
                          "integrate and nothing to verify; is it the walk's log?",
                          imu.source,
                          imu.time_s.back() - imu.time_s.front()));
}

void AddWalkFindings(const StillResult& still,
                     std::size_t samples,
                     bool log_has_gyro,
                     bool gyro_asked,
                     std::vector<VerifyFinding>& findings) {
  const auto mid_stops = std::count_if(
      still.intervals.begin(), still.intervals.end(), [samples](const auto& s) {
        return s.first > 0 && s.second < samples;
      });
  if (mid_stops == 0) {
    findings.push_back(
        Finding(VerifyFindingKind::kNoStop,
                "no stop detected during the walk: without zero-velocity updates "
                "between the rests at the ends, the position error of a bias grows "
                "with the square of the walking time"));
  }
  if (log_has_gyro && !gyro_asked) {
    findings.push_back(Finding(VerifyFindingKind::kGyroscopeUnused,
                               "the log has gyroscope columns, but they were not used"));
  }
}

}  // namespace mpcal::internal
