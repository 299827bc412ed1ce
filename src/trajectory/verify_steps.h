// The steps of Verify (verify.cc), one rule each, private to the trajectory
// room: checking the inputs, finding the start of motion in the log and in
// the reference, aligning the clocks, cutting the reference to the overlap
// and finding the epoch that fixes the initial heading. Tests reach them
// through this header.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "mpcal/verify.h"

namespace mpcal::internal {

// Departure from the first position that counts as "moving" (m): well above
// RTK noise, well below a few steps.
inline constexpr double kDepartureM = 0.5;
// Clocks that disagree with the start of motion by more than this get a
// finding (s).
inline constexpr double kClockDisagreementS = 2.0;

/// The inputs' sizes, units and options checked; returns the log's m/s² per
/// unit. Throws mpcal::Error (kOption, kInput or kUnits, with the units to
/// read the log in as advice).
double CheckVerifyInputs(const Recording& imu,
                         const GnssTrack& reference,
                         const std::optional<Calibration>& calibration,
                         const VerifyOptions& options);

/// When the reference leaves its first position: the last epoch before the
/// first departure of kDepartureM still within the rest jitter; empty when
/// it never departs.
std::optional<double> ReferenceMotionStart(const TimedPath& ref);

/// When the walking starts in the log: after the initial rest, the first
/// sample from which the motion stays at walking level for most of the next
/// few seconds; empty without an initial rest or any motion.
std::optional<std::size_t> ImuMotionStart(const StillResult& still,
                                          std::span<const double> time_s);

/// The offset (t_reference = t_imu + offset) near `offset_s` that best
/// matches the distance from the start of `imu_path` with the reference's
/// over the first seconds of motion; `offset_s` when too few epochs.
double RefineOffset(double offset_s,
                    const TimedPath& imu_path,
                    double imu_motion_start_s,
                    const TimedPath& ref);

/// The time spans of the log and of the reference, each on its own clock (s).
struct ClockSpans {
  double imu_begin_s = 0.0;
  double imu_end_s = 0.0;
  double ref_begin_s = 0.0;
  double ref_end_s = 0.0;
};

/// kAuto resolved: the common clock when the spans overlap by at least half
/// of the shorter one, or when no start-of-motion offset was found; the start
/// of motion otherwise. Other modes are returned as they are.
TimeAlignMode ResolveAlignMode(TimeAlignMode requested,
                               const ClockSpans& spans,
                               bool has_motion_offset);

/// Why the start of motion gave no offset, for the error when it is asked for.
struct MotionStartMissing {
  bool imu_has_no_rest = false;
  std::string imu_source;
  std::string reference_source;
};

/// The clocks aligned by `options` (method, offset, overlap), from the
/// start-of-motion offset in `time.motion_offset_s`. Appends a
/// kClockDisagreement finding when the common clock disagrees with the start
/// of motion. Throws mpcal::Error (kTime) when the start of motion is asked
/// for but missing, or the overlap is shorter than options.min_overlap_s.
void AlignClocks(const ClockSpans& spans,
                 const VerifyOptions& options,
                 const MotionStartMissing& missing,
                 TimeAlignment& time,
                 std::vector<VerifyFinding>& findings);

/// The reference epochs within [overlap_start_s, overlap_end_s] into
/// result.reference_path / reference_quality, with the reference's figures.
/// Throws mpcal::Error (kInput) for fewer than two.
void CutReferenceToOverlap(const GnssTrack& reference,
                           double path_step_m,
                           VerifyResult& result);

/// The time of the first epoch at least `distance_m` horizontally from the
/// first one: the end of the segment that gives the initial heading.
std::optional<double> HeadingTime(const TimedPath& ref, double distance_m);

/// Throws mpcal::Error (kInput) when the still test finds `imu` at rest
/// throughout: the zero-velocity updates would hold both trajectories at
/// their start, and 0 m from start to end would pass for a perfect
/// calibration.
void ThrowIfNeverMoves(const StillResult& still, const Recording& imu);

/// The findings about the walk itself (no stop in the middle, gyroscope
/// columns left out), appended to `findings`.
void AddWalkFindings(const StillResult& still,
                     std::size_t samples,
                     bool log_has_gyro,
                     bool gyro_asked,
                     std::vector<VerifyFinding>& findings);

}  // namespace mpcal::internal
