/// \file verify.h
/// \brief Field verification of a calibration against a GNSS reference
/// (docs/method.md §5, the paper's section 5.2): align the IMU log with the
/// reference in time, integrate the readings raw and corrected to two
/// trajectories, place them at the first reference point with the reference's
/// initial heading, and report for each the start-to-end distance (the paper's
/// Table 7), the horizontal RMS and maximum distance to the reference and the
/// path length. The result's files are written in mpcal/verification_file.h.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "mpcal/advice.h"
#include "mpcal/calibration.h"
#include "mpcal/check.h"
#include "mpcal/gnss.h"
#include "mpcal/recording.h"
#include "mpcal/trajectory.h"

namespace mpcal {

/// How the IMU clock is related to the reference clock.
enum class TimeAlignMode {
  /// Common clock when the two time spans overlap by at least half of the
  /// shorter one; otherwise from the start of motion.
  kAuto,
  /// Both on one clock (e.g. unix time stamped from the receiver).
  kCommonClock,
  /// t_reference = t_imu + offset_s, the user's offset.
  kOffset,
  /// From the start of motion in both: the end of the initial rest in the
  /// IMU log and the departure of the reference from its first position,
  /// refined by matching the distance from the start over the first seconds.
  kMotionStart,
};
/// "auto", "common", "offset" or "motion".
std::string_view ToString(TimeAlignMode mode);
std::optional<TimeAlignMode> ParseTimeAlignMode(std::string_view name);

struct VerifyOptions {
  /// Time alignment; `time_offset_s` is used with kOffset.
  TimeAlignMode time_align = TimeAlignMode::kAuto;
  double time_offset_s = 0.0;
  /// Shortest overlap of the IMU log and the reference accepted (s).
  double min_overlap_s = 5.0;
  /// Integration (gravity, mount, gyroscope, zero-velocity updates).
  IntegrateOptions integrate;
  /// The still test behind levelling and zero-velocity updates.
  StillOptions still;
  /// The initial heading is taken from the start to the first reference
  /// point at least this far away horizontally (m).
  double heading_distance_m = 5.0;
  /// Path lengths count only steps of at least this length (m), so that the
  /// reference's jitter at rest does not add up.
  double path_step_m = 0.25;

  /// "" when valid, otherwise names the first bad field.
  std::string Validate() const;
};

struct TimeAlignment {
  TimeAlignMode method = TimeAlignMode::kCommonClock;
  /// t_reference = t_imu + offset_s.
  double offset_s = 0.0;
  /// The common span, on the reference clock (s).
  double overlap_start_s = 0.0;
  double overlap_end_s = 0.0;
  /// The offset the start of motion suggests, when it could be found.
  std::optional<double> motion_offset_s;
};

/// Figures of the reference over the overlap.
struct ReferenceMetrics {
  double path_length_m = 0.0;
  double start_end_distance_m = 0.0;
  std::size_t epochs = 0;
};

/// What a verification found that the user should know.
enum class VerifyFindingKind {
  /// On the common clock the start of motion differs between the log and
  /// the reference by more than 2 s (`motion_offset_s`): the clocks may
  /// differ. Advice: align by the start of motion, or give the offset.
  kClockDisagreement,
  /// No stop between the rests at the ends: no zero-velocity updates.
  kNoStop,
  /// The log has gyroscope columns, but the options left them out.
  kGyroscopeUnused,
};

/// One finding: its kind, the figures, a plain sentence (no flags) and what
/// would change it, as facts (the caller words the advice).
struct VerifyFinding {
  VerifyFindingKind kind = VerifyFindingKind::kNoStop;
  std::string what;
  /// kClockDisagreement: the offset the start of motion suggests (s).
  double motion_offset_s = 0.0;
  Advice advice;
};

struct VerifyResult {
  TimeAlignment time;
  ReferenceMetrics reference;
  PathMetrics raw;
  /// Only with a calibration.
  std::optional<PathMetrics> corrected;
  /// For plotting, on the reference clock and in its east-north-up frame:
  /// the reference over the overlap and the aligned trajectories (IMU rate).
  TimedPath reference_path;
  std::vector<int> reference_quality;
  TimedPath raw_path;
  std::optional<TimedPath> corrected_path;
  /// How the integration went (of the raw run; the corrected one shares the
  /// still samples and the gyroscope).
  MountMode mount = MountMode::kLevel;
  double gravity_mps2 = 0.0;
  bool gyro_used = false;
  double initial_rest_s = 0.0;
  double initial_tilt_raw_rad = 0.0;
  int stops = 0;
  double heading_rotation_rad = 0.0;
  /// Things the user should know (clock disagreement, no stop detected, ...).
  std::vector<VerifyFinding> findings;
  /// The findings as the result file and the report state them: `what` of
  /// each finding, in order, unless the caller words them its own way (the
  /// `mpcal` command puts its advice in).
  std::vector<std::string> warnings;
};

/// Runs the verification.
/// \param imu the walk's log (units g or m/s²; gyroscope optional)
/// \param reference the GNSS track (east-north-up)
/// \param calibration when given, a second trajectory from corrected readings
/// \throws mpcal::Error for invalid options, a log in counts, a calibration
///   for other units than the log's, an empty input, logs that do not overlap
///   in time (the message gives both spans), no initial rest where one is
///   needed, an IMU log at rest throughout, or a reference that never moves.
VerifyResult Verify(const Recording& imu,
                    const GnssTrack& reference,
                    const std::optional<Calibration>& calibration,
                    const VerifyOptions& options);

/// A verification's checks: the correction (is the corrected walk closer to
/// the reference than the raw one, by the horizontal RMS over the whole
/// walk), the clock (do the IMU's and the reference's starts of motion agree
/// on the offset used), the stops (zero-velocity updates between the end
/// rests) and the gyroscope (did it carry the attitude). A corrected walk no
/// closer than the raw one is to be looked at, not refused: a level mount
/// absorbs a constant bias, so a good calibration can leave the walk as it
/// was; what it says is that this walk does not confirm the calibration.
std::vector<Check> JudgeVerification(const VerifyResult& result);

}  // namespace mpcal
