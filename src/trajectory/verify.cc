// Field verification: time alignment, raw and corrected integration, metrics.
#include "mpcal/verify.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "mpcal/error.h"
#include "mpcal/units.h"

namespace mpcal {
namespace {

// Departure from the first position that counts as "moving" (m): well above
// RTK noise, well below a few steps.
constexpr double kDepartureM = 0.5;
// Window after the start of motion over which the clocks are matched (s), and
// the search range around the first guess (s).
constexpr double kRefineWindowS = 5.0;
constexpr double kRefineRangeS = 1.5;
constexpr double kRefineStepS = 0.005;
// Clocks that disagree with the start of motion by more than this get a
// warning (s).
constexpr double kClockDisagreementS = 2.0;
// Walking is motion that lasts at least this long (s).
constexpr double kSustainedMotionS = 3.0;

double HorizontalDistance(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::hypot(a.x() - b.x(), a.y() - b.y());
}

// When the reference leaves its first position: the last epoch before the
// first departure of kDepartureM still within the rest jitter.
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

// Refines an offset by matching the distance from the start (which does not
// depend on heading) of a levelled integration with the reference over the
// first seconds of motion.
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

std::string Span(double a, double b) { return fmt::format("{:.3f} .. {:.3f} s", a, b); }

// When the walking starts: after the initial rest, the first sample from
// which the motion statistic stays at a quarter of its typical level in
// motion for most of the next few seconds. Picking the device up before
// setting off is shorter than that, and is not taken for the start.
std::optional<std::size_t> ImuMotionStart(const StillResult& still,
                                          std::span<const double> time_s) {
  const std::size_t n = still.still.size();
  if (still.initial_rest_end == 0 || still.initial_rest_end >= n) return std::nullopt;
  std::vector<double> moving;
  for (std::size_t i = 0; i < n; ++i) {
    if (!still.still[i]) moving.push_back(still.accel_std_mps2[i]);
  }
  if (moving.empty()) return std::nullopt;
  const auto mid = moving.begin() + static_cast<std::ptrdiff_t>(moving.size() / 2);
  std::nth_element(moving.begin(), mid, moving.end());
  const double walking = std::max(0.25 * *mid, still.accel_threshold_mps2);
  // Prefix counts of samples at the walking level.
  std::vector<std::size_t> above(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    above[i + 1] = above[i] + (still.accel_std_mps2[i] >= walking ? 1 : 0);
  }
  std::size_t j = still.initial_rest_end;
  for (std::size_t i = still.initial_rest_end; i < n; ++i) {
    if (still.accel_std_mps2[i] < walking) continue;
    while (j < n && time_s[j] < time_s[i] + kSustainedMotionS) ++j;
    if (j == n) break;
    if (static_cast<double>(above[j] - above[i]) >= 0.8 * static_cast<double>(j - i))
      return i;
  }
  return std::nullopt;
}

}  // namespace

std::string_view ToString(TimeAlignMode mode) {
  switch (mode) {
    case TimeAlignMode::kAuto:
      return "auto";
    case TimeAlignMode::kCommonClock:
      return "common";
    case TimeAlignMode::kOffset:
      return "offset";
    case TimeAlignMode::kMotionStart:
      return "motion";
  }
  return "auto";
}

std::optional<TimeAlignMode> ParseTimeAlignMode(std::string_view name) {
  for (const TimeAlignMode m : {TimeAlignMode::kAuto,
                                TimeAlignMode::kCommonClock,
                                TimeAlignMode::kOffset,
                                TimeAlignMode::kMotionStart}) {
    if (name == ToString(m)) return m;
  }
  return std::nullopt;
}

std::string VerifyOptions::Validate() const {
  if (!std::isfinite(time_offset_s)) return "time_offset_s must be finite";
  if (!(min_overlap_s > 0.0)) return "min_overlap_s must be positive";
  if (!(heading_distance_m > 0.0)) return "heading_distance_m must be positive";
  if (!(path_step_m >= 0.0)) return "path_step_m must be >= 0";
  if (std::string p = integrate.Validate(); !p.empty()) return "integrate." + p;
  if (std::string p = still.Validate(); !p.empty()) return "still." + p;
  return "";
}

VerifyResult Verify(const Recording& imu,
                    const GnssTrack& reference,
                    const std::optional<Calibration>& calibration,
                    const VerifyOptions& options) {
  if (const std::string p = options.Validate(); !p.empty()) {
    throw Error("verify options: " + p);
  }
  const std::size_t n = imu.size();
  if (n < 3 || imu.accel.size() != n) {
    throw Error(fmt::format(
        "{}: the IMU log has {} samples; a walk needs many more", imu.source, n));
  }
  if (!imu.gyro_radps.empty() && imu.gyro_radps.size() != n) {
    throw Error(fmt::format("{}: {} gyroscope readings for {} samples",
                            imu.source,
                            imu.gyro_radps.size(),
                            n));
  }
  if (reference.size() < 2) {
    throw Error(fmt::format("{}: the reference has {} epochs; a walk needs many more",
                            reference.source,
                            reference.size()));
  }
  const std::optional<double> scale = FixedMps2PerUnit(imu.units);
  if (!scale) {
    throw Error(fmt::format(
        "{}: the log is in raw counts, which have no physical scale to integrate; "
        "convert it to g or m/s2 first (mpcal apply), or read it with --units g|mps2",
        imu.source));
  }
  if (calibration && calibration->input_units != imu.units) {
    throw Error(fmt::format(
        "the calibration is for logs in {}, but {} is read as {}; pass --units {}",
        ToString(calibration->input_units),
        imu.source,
        ToString(imu.units),
        ToString(calibration->input_units)));
  }

  VerifyResult result;
  result.mount = options.integrate.mount;
  result.gravity_mps2 = options.integrate.gravity_mps2;

  std::vector<Eigen::Vector3d> raw(n);
  for (std::size_t i = 0; i < n; ++i) raw[i] = imu.accel[i] * *scale;
  std::vector<Eigen::Vector3d> corrected;
  if (calibration) {
    corrected.resize(n);
    for (std::size_t i = 0; i < n; ++i) corrected[i] = calibration->Correct(imu.accel[i]);
  }
  const StillResult still = DetectStill(imu.time_s, raw, imu.gyro_radps, options.still);
  result.initial_rest_s = still.initial_rest_end > 0
                              ? imu.time_s[still.initial_rest_end - 1] - imu.time_s[0]
                              : 0.0;
  result.stops = static_cast<int>(still.intervals.size());

  TimedPath ref_all;
  ref_all.time_s = reference.time_s;
  ref_all.position_m = reference.enu_m;

  // --- time alignment --------------------------------------------------
  const double imu_begin = imu.time_s.front();
  const double imu_end = imu.time_s.back();
  const double ref_begin = reference.time_s.front();
  const double ref_end = reference.time_s.back();
  const std::optional<std::size_t> imu_motion_index = ImuMotionStart(still, imu.time_s);
  const std::optional<double> imu_motion =
      imu_motion_index ? std::optional<double>(imu.time_s[*imu_motion_index])
                       : std::nullopt;
  const std::optional<double> ref_motion = ReferenceMotionStart(ref_all);
  if (imu_motion && ref_motion) {
    double offset = *ref_motion - *imu_motion;
    if (result.initial_rest_s >= options.integrate.min_initial_rest_s) {
      // A levelled integration, whatever the mount: over a few seconds the
      // bias cannot move it much, and the distance does not need a heading.
      // The corrected readings when there are some: a walk that turns from
      // the start leaks the raw bias at once.
      IntegrateOptions level = options.integrate;
      level.mount = MountMode::kLevel;
      const IntegrationResult run = IntegrateTrajectory(
          imu.time_s, calibration ? corrected : raw, imu.gyro_radps, still, level);
      offset = RefineOffset(offset, run.path, *imu_motion, ref_all);
    }
    result.time.motion_offset_s = offset;
  }
  const double common_overlap =
      std::min(imu_end, ref_end) - std::max(imu_begin, ref_begin);
  TimeAlignMode method = options.time_align;
  if (method == TimeAlignMode::kAuto) {
    const double shorter = std::min(imu_end - imu_begin, ref_end - ref_begin);
    method = common_overlap >= 0.5 * shorter || !result.time.motion_offset_s
                 ? TimeAlignMode::kCommonClock
                 : TimeAlignMode::kMotionStart;
  }
  result.time.method = method;
  switch (method) {
    case TimeAlignMode::kCommonClock:
    case TimeAlignMode::kAuto:
      result.time.offset_s = 0.0;
      if (result.time.motion_offset_s &&
          std::abs(*result.time.motion_offset_s) > kClockDisagreementS) {
        result.warnings.push_back(fmt::format(
            "on the common clock the start of motion differs by {:.2f} s between the IMU "
            "log "
            "and the reference{}; if the clocks differ, pass --time-align motion or "
            "--time-offset",
            *result.time.motion_offset_s,
            std::abs(std::abs(*result.time.motion_offset_s) - 18.0) < 1.0
                ? " (18 s is GPS time minus UTC)"
                : ""));
      }
      break;
    case TimeAlignMode::kOffset:
      result.time.offset_s = options.time_offset_s;
      break;
    case TimeAlignMode::kMotionStart:
      if (!result.time.motion_offset_s) {
        throw Error(fmt::format(
            "cannot align the clocks by the start of motion: {}; give --time-offset",
            !imu_motion ? fmt::format("{} does not start at rest", imu.source)
                        : fmt::format("{} never moves {} m from its first position",
                                      reference.source,
                                      kDepartureM)));
      }
      result.time.offset_s = *result.time.motion_offset_s;
      break;
  }
  const double offset = result.time.offset_s;
  result.time.overlap_start_s = std::max(imu_begin + offset, ref_begin);
  result.time.overlap_end_s = std::min(imu_end + offset, ref_end);
  if (result.time.overlap_end_s - result.time.overlap_start_s < options.min_overlap_s) {
    throw Error(fmt::format(
        "the IMU log and the reference do not overlap in time: the log covers {} and the "
        "reference {} (reference clock, {} alignment, offset {:.3f} s); they need at "
        "least "
        "{} s in common. Use --time-align motion to align by the start of motion, or "
        "--time-offset SECONDS (GPS time is 18 s ahead of UTC)",
        Span(imu_begin + offset, imu_end + offset),
        Span(ref_begin, ref_end),
        ToString(method),
        offset,
        options.min_overlap_s));
  }

  // --- the reference over the overlap -----------------------------------
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
        fmt::format("{}: fewer than two reference epochs within the IMU log's span",
                    reference.source));
  }
  result.reference.epochs = ref.size();
  result.reference.path_length_m =
      HorizontalPathLength(ref.position_m, options.path_step_m);
  result.reference.start_end_distance_m =
      HorizontalDistance(ref.position_m.back(), ref.position_m.front());
  const double t_start = ref.time_s.front();
  std::optional<double> t_heading;
  for (std::size_t i = 0; i < ref.size() && !t_heading; ++i) {
    if (HorizontalDistance(ref.position_m[i], ref.position_m.front()) >=
        options.heading_distance_m) {
      t_heading = ref.time_s[i];
    }
  }
  if (!t_heading) {
    throw Error(fmt::format(
        "{}: the reference never moves {} m from its first position within the IMU log's "
        "span, so the initial heading cannot be found; is it the walk?",
        reference.source,
        options.heading_distance_m));
  }

  // --- integration, raw and corrected -------------------------------------
  const auto run = [&](const std::vector<Eigen::Vector3d>& force,
                       PathMetrics& metrics,
                       TimedPath& out) {
    IntegrationResult r =
        IntegrateTrajectory(imu.time_s, force, imu.gyro_radps, still, options.integrate);
    for (double& t : r.path.time_s) t += offset;
    const double angle = AlignToReference(r.path, ref, t_start, *t_heading);
    metrics = ComparePaths(r.path, ref, options.path_step_m);
    // Keep the overlap only: that is what the metrics are about.
    for (std::size_t i = 0; i < r.path.size(); ++i) {
      if (r.path.time_s[i] < result.time.overlap_start_s ||
          r.path.time_s[i] > result.time.overlap_end_s) {
        continue;
      }
      out.time_s.push_back(r.path.time_s[i]);
      out.position_m.push_back(r.path.position_m[i]);
    }
    return std::make_pair(r, angle);
  };
  const auto [raw_run, raw_angle] = run(raw, result.raw, result.raw_path);
  result.gyro_used = raw_run.gyro_used;
  result.initial_tilt_raw_rad = raw_run.initial_tilt_rad;
  result.heading_rotation_rad = raw_angle;
  if (calibration) {
    result.corrected.emplace();
    result.corrected_path.emplace();
    run(corrected, *result.corrected, *result.corrected_path);
  }
  const auto mid_stops =
      std::count_if(still.intervals.begin(), still.intervals.end(), [n](const auto& s) {
        return s.first > 0 && s.second < n;
      });
  if (mid_stops == 0) {
    result.warnings.push_back(
        "no stop detected during the walk: without zero-velocity updates between the "
        "rests "
        "at the ends, the position error of a bias grows with the square of the walking "
        "time");
  }
  if (!imu.gyro_radps.empty() && !options.integrate.use_gyro) {
    result.warnings.push_back("the log has gyroscope columns, but they were not used");
  }
  return result;
}

}  // namespace mpcal
