// Field verification: time alignment, raw and corrected integration, metrics.
#include "mpcal/verify.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "mpcal/error.h"
#include "mpcal/units.h"
#include "trajectory/verify_steps.h"

namespace mpcal {
namespace {

using internal::ClockSpans;

// The offset the start of motion suggests (t_reference = t_imu + offset),
// refined by matching distances when the log starts with a long enough rest.
std::optional<double> MotionOffset(const Recording& imu,
                                   const std::vector<Eigen::Vector3d>& force_mps2,
                                   const StillResult& still,
                                   const TimedPath& reference,
                                   double initial_rest_s,
                                   const VerifyOptions& options,
                                   internal::MotionStartMissing& missing) {
  const std::optional<std::size_t> imu_motion_index =
      internal::ImuMotionStart(still, imu.time_s);
  const std::optional<double> ref_motion = internal::ReferenceMotionStart(reference);
  missing.imu_has_no_rest = !imu_motion_index;
  if (!imu_motion_index || !ref_motion) return std::nullopt;
  const double imu_motion = imu.time_s[*imu_motion_index];
  const double offset = *ref_motion - imu_motion;
  if (initial_rest_s < options.integrate.min_initial_rest_s) return offset;
  // A levelled integration, whatever the mount: over a few seconds the bias
  // cannot move it much, and the distance does not need a heading. The
  // corrected readings when there are some: a walk that turns from the start
  // leaks the raw bias at once.
  IntegrateOptions level = options.integrate;
  level.mount = MountMode::kLevel;
  const IntegrationResult run =
      IntegrateTrajectory(imu.time_s, force_mps2, imu.gyro_radps, still, level);
  return internal::RefineOffset(offset, run.path, imu_motion, reference);
}

// One integration (raw or corrected) on the reference clock, rotated onto the
// reference's initial heading, compared with it, and kept over the overlap
// only (that is what the metrics are about). Returns the integration and the
// heading rotation (rad).
std::pair<IntegrationResult, double> IntegrateAligned(
    const Recording& imu,
    const std::vector<Eigen::Vector3d>& force_mps2,
    const StillResult& still,
    const VerifyOptions& options,
    double t_heading_s,
    const VerifyResult& result,
    PathMetrics& metrics,
    TimedPath& out) {
  IntegrationResult r = IntegrateTrajectory(
      imu.time_s, force_mps2, imu.gyro_radps, still, options.integrate);
  for (double& t : r.path.time_s) t += result.time.offset_s;
  const TimedPath& ref = result.reference_path;
  const double angle = AlignToReference(r.path, ref, ref.time_s.front(), t_heading_s);
  metrics = ComparePaths(r.path, ref, options.path_step_m);
  for (std::size_t i = 0; i < r.path.size(); ++i) {
    if (r.path.time_s[i] < result.time.overlap_start_s ||
        r.path.time_s[i] > result.time.overlap_end_s) {
      continue;
    }
    out.time_s.push_back(r.path.time_s[i]);
    out.position_m.push_back(r.path.position_m[i]);
  }
  return {std::move(r), angle};
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
  const double scale = internal::CheckVerifyInputs(imu, reference, calibration, options);
  const std::size_t n = imu.size();
  VerifyResult result;
  result.mount = options.integrate.mount;
  result.gravity_mps2 = options.integrate.gravity_mps2;

  std::vector<Eigen::Vector3d> raw(n);
  for (std::size_t i = 0; i < n; ++i) raw[i] = imu.accel[i] * scale;
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
  internal::ThrowIfNeverMoves(still, imu);

  TimedPath ref_all;
  ref_all.time_s = reference.time_s;
  ref_all.position_m = reference.enu_m;
  internal::MotionStartMissing missing;
  missing.imu_source = imu.source;
  missing.reference_source = reference.source;
  result.time.motion_offset_s = MotionOffset(imu,
                                             calibration ? corrected : raw,
                                             still,
                                             ref_all,
                                             result.initial_rest_s,
                                             options,
                                             missing);
  const ClockSpans spans{.imu_begin_s = imu.time_s.front(),
                         .imu_end_s = imu.time_s.back(),
                         .ref_begin_s = reference.time_s.front(),
                         .ref_end_s = reference.time_s.back()};
  internal::AlignClocks(spans, options, missing, result.time, result.findings);
  internal::CutReferenceToOverlap(reference, options.path_step_m, result);
  const std::optional<double> t_heading =
      internal::HeadingTime(result.reference_path, options.heading_distance_m);
  if (!t_heading) {
    throw Error(ErrorKind::kInput,
                fmt::format("{}: the reference never moves {} m from its first position "
                            "within the IMU log's span, so the initial heading cannot be "
                            "found; is it the walk?",
                            reference.source,
                            options.heading_distance_m));
  }

  const auto [raw_run, raw_angle] = IntegrateAligned(
      imu, raw, still, options, *t_heading, result, result.raw, result.raw_path);
  result.gyro_used = raw_run.gyro_used;
  result.initial_tilt_raw_rad = raw_run.initial_tilt_rad;
  result.heading_rotation_rad = raw_angle;
  if (calibration) {
    result.corrected.emplace();
    result.corrected_path.emplace();
    IntegrateAligned(imu,
                     corrected,
                     still,
                     options,
                     *t_heading,
                     result,
                     *result.corrected,
                     *result.corrected_path);
  }
  internal::AddWalkFindings(
      still, n, !imu.gyro_radps.empty(), options.integrate.use_gyro, result.findings);
  for (const VerifyFinding& finding : result.findings) {
    result.warnings.push_back(finding.what);
  }
  return result;
}

}  // namespace mpcal
