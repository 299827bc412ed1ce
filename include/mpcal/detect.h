/// \file detect.h
/// \brief Finding the static positions in a continuous recording.
///
/// A sample is still when the moving standard deviation of the readings over
/// a short window is below a threshold taken from the recording's own quiet
/// level (a low quantile of that statistic), not a constant: it works the
/// same in counts, g or m/s². Runs of still samples become intervals; the
/// settling after each turn is trimmed; neighbouring intervals at the same
/// orientation separated by a short bump are merged; intervals shorter than
/// the minimum are dropped and counted.
///
/// The motion statistic at sample i is the norm of the per-axis standard
/// deviations over the centred window of `window_s` around it,
/// sqrt(var_x + var_y + var_z), computed from running sums in O(n). A window
/// is low only when every sample in it is still, so a run of low-statistic
/// centres already lies half a window inside the still stretch: the smear of
/// the moving window costs nothing at the ends; the settling is trimmed
/// explicitly by `settle_s`.
///
/// The threshold is `threshold_factor` × the quiet level, capped at
/// `max_still_g` (in g, turned into the recording's units with the radius of a
/// sphere fitted to one-window means: no scale needs to be known for raw
/// counts). The cap is what lets a recording that never stops moving come out
/// empty, with the reason, instead of its least-moving stretches being taken
/// for positions: its quiet level is a motion level.
///
/// StillnessMonitor applies the same rule to rows as they arrive, for a
/// caller that streams a long log: whether it was still throughout.
#pragma once

#include <cstddef>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mpcal/advice.h"
#include "mpcal/recording.h"
#include "mpcal/recording_view.h"

namespace mpcal {

struct DetectOptions {
  /// Length of the moving window of the motion statistic (s). Longer rejects
  /// slow drifts of the hand better, shorter resolves short positions.
  double window_s = 1.0;
  /// Shortest static interval kept, after trimming (s). Lower it for quick
  /// sessions (positions held 2-3 s); the paper holds each 40-60 s.
  double min_static_s = 2.0;
  /// Trimmed from each end of an interval to drop settling (s).
  double settle_s = 0.3;
  /// Threshold = this factor × the quiet level of the recording. Raise it
  /// (5-10) when a hand-held sensor trembles more in some positions than in
  /// the quietest ones and positions are missed; lower it (2) when turns
  /// leak into intervals.
  double threshold_factor = 3.0;
  /// Quantile of the motion statistic over the recording taken as its quiet
  /// level (0-1). Robust as long as more than about twice this fraction of
  /// the recording is still; 0.05 keeps recordings that are 90 % motion
  /// working.
  double quiet_quantile = 0.05;
  /// Cap of the threshold (g): no stretch whose motion statistic exceeds
  /// this is still, whatever the quiet level. A hand holding a sensor still
  /// stays within a few mg; a turn of 10 deg/s over a 1 s window is 0.05 g.
  /// Raise it for a sensor noisier than this at rest; 0 disables the cap.
  double max_still_g = 0.05;
  /// Intervals closer than this in time (s) and in orientation (deg) merge.
  double merge_gap_s = 1.0;
  double merge_angle_deg = 3.0;
  /// Measuring range of the sensor (m/s², per axis, e.g. 19.6 for ±2 g): a
  /// reading at or beyond 99 % of it in magnitude is clipped (for raw counts
  /// about the centre of the sphere the readings lie on). 0 = find the limits
  /// from the data: an axis's largest or smallest value, at least 1.5 g from
  /// that centre and repeated in a run of at least 3 identical samples (a
  /// sensor held still never reads 1.5 g; a saturated one sticks at its
  /// limit). Clipped samples are left out of the quiet level, and a position
  /// that contains any is dropped (DetectResult::dropped_clipped) with a
  /// warning naming its time: its mean would be biased. Give the range for a
  /// sensor whose range is below 1.5 g, or a large value to disable the check.
  double range_mps2 = 0.0;

  /// Empty string when valid, otherwise names the first bad field.
  std::string Validate() const;
};

/// One still position.
struct StaticInterval {
  std::size_t begin = 0;  ///< first sample index (inclusive)
  std::size_t end = 0;    ///< one past the last sample index
  double start_s = 0.0;
  double end_s = 0.0;
  /// Mean and per-axis sample standard deviation of the readings, in the
  /// recording's units, over the kept samples (a merged bump excluded).
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Vector3d std = Eigen::Vector3d::Zero();
  /// Samples inside [begin, end) left out of mean and std: the bump (and its
  /// settling) between two merged pieces. 0 for an interval not merged.
  std::size_t excluded = 0;
  /// Samples behind mean and std.
  std::size_t samples() const { return end - begin - excluded; }
  double duration_s() const { return end_s - start_s; }
  /// Noise level: the norm of `std` (recording units).
  double noise() const { return std.norm(); }
};

/// What detection concluded, as a kind.
enum class DetectOutcome {
  kFound,       ///< at least one static position
  kNeverStill,  ///< no window was still: the sensor never stops moving
  kTooShort,    ///< still stretches, none long enough after trimming
  kAllClipped,  ///< positions found, every one dropped for clipping
};

/// Why detection found what it found, with the figures behind it and what
/// would change it. Describe() turns it into a plain sentence; the command
/// line spells the advice as its flags.
struct DetectFinding {
  DetectOutcome kind = DetectOutcome::kFound;
  double span_s = 0.0;  ///< time the recording covers
  /// The options that decided it.
  double window_s = 0.0;
  double min_static_s = 0.0;
  double settle_s = 0.0;
  double threshold_factor = 0.0;
  double quiet_quantile = 0.0;
  double max_still_g = 0.0;
  /// The figures (recording units unless named): as in DetectResult.
  double threshold = 0.0;
  bool threshold_capped = false;
  double quiet_level = 0.0;
  double quiet_g = 0.0;  ///< the quiet level in g (0 when unknown)
  double longest_still_s = 0.0;
  int dropped_short = 0;
  int dropped_clipped = 0;
  /// The range limits the clipped readings reached, e.g. "|x| >= 8.73773".
  std::string clip_limits;
  /// kTooShort: the minimum and settling the longest stretch would pass.
  double suggested_min_static_s = 0.0;
  double suggested_settle_s = 0.0;
  /// The options that would change the outcome (any one of them), with the
  /// values the data suggest.
  Advice advice;
};

/// A finding about one position or the whole recording that does not stop
/// detection.
enum class DetectNoteKind {
  kClippedPosition,  ///< a position dropped: readings at the range limit
  kNotStill,         ///< even the quietest part moves more than a still sensor
};

struct DetectNote {
  DetectNoteKind kind = DetectNoteKind::kClippedPosition;
  /// kClippedPosition: the position (log clock), its clipped samples and the
  /// limits they reached.
  double start_s = 0.0;
  double end_s = 0.0;
  std::size_t clipped_samples = 0;
  std::string clip_limits;
  /// kNotStill: the quiet level in g, over the quietest fraction, and the
  /// most a still MEMS accelerometer shows (g).
  double quiet_g = 0.0;
  double quiet_quantile = 0.0;
  double plausible_quiet_g = 0.0;
  Advice advice;
};

/// The finding as plain sentences (no option names): its facts, then what
/// to do. DescribeFacts() is the first part alone, for a caller that words
/// the advice itself.
std::string Describe(const DetectFinding& finding);
std::string DescribeFacts(const DetectFinding& finding);
std::string Describe(const DetectNote& note);
std::string DescribeFacts(const DetectNote& note);

struct DetectResult {
  std::vector<StaticInterval> intervals;
  /// Quiet level of the motion statistic and the threshold used (recording
  /// units).
  double quiet_level = 0.0;
  double threshold = 0.0;
  /// One g in the recording's units, as the cap used it (exact for g and
  /// m/s², estimated for counts), and whether the cap lowered the threshold.
  double gravity_units = 0.0;
  bool threshold_capped = false;
  /// Still stretches dropped for being shorter than min_static_s.
  int dropped_short = 0;
  /// Pairs of intervals merged across a short bump.
  int merged = 0;
  /// Samples at the sensor's range limit (see DetectOptions::range_mps2), and
  /// the positions dropped because they contain some.
  std::size_t clipped_samples = 0;
  int dropped_clipped = 0;
  /// Non-fatal findings (a position dropped for clipping, with its time in
  /// the log's clock; a recording that is never still), in order.
  std::vector<DetectNote> notes;
  /// Longest still stretch found (s, before trimming), kept or not, and the
  /// fraction of the samples that were still.
  double longest_still_s = 0.0;
  double still_fraction = 0.0;
  /// Moving window in samples and the typical sample period (s).
  std::size_t window_samples = 0;
  double sample_period_s = 0.0;
  /// Why the intervals are what they are: kFound, or why none was found,
  /// with the figures and what to try.
  DetectFinding finding;
};

/// The turn between two neighbouring static positions, as the gyroscope
/// measured it (see MeasureTurns in calibrate.h).
struct Turn {
  std::size_t from = 0;  ///< index of the position before (the one after: from + 1)
  double start_s = 0.0;  ///< end of the position before (log clock)
  double end_s = 0.0;    ///< start of the position after
  double duration_s() const { return end_s - start_s; }
  /// Rotation angle (deg) and unit axis (sensor frame at the start), with
  /// the bias measured at the two positions taken out.
  double angle_deg = 0.0;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  /// Angle between the gravity directions measured at the two positions
  /// (deg): the part of the turn the accelerometer sees.
  double tilt_deg = 0.0;
};

/// Finds the static positions of `recording` (any units; time must increase).
/// \throws mpcal::Error if the recording is empty or too short for one
///   window, its time does not increase, a reading is not finite, or the
///   options are invalid.
DetectResult DetectStatic(const RecordingView& recording, const DetectOptions& options);

/// Why a record is not still throughout (StillVerdict::reason).
enum class NotStillReason {
  kNone,        ///< still throughout
  kMoved,       ///< a window's motion statistic is above the threshold
  kRangeLimit,  ///< a reading at the sensor's range limit
  kGap,         ///< a time step longer than the detection window
  kTooShort,    ///< no verdict: fewer rows than one window, or raw counts
  kNotFinite,   ///< a time or reading that is not finite
};

/// Whether a record is still from its first row to its last, by static
/// detection's rule, and the figures behind it. Figures in the recording's
/// units, times in the log's clock.
struct StillVerdict {
  bool still = false;  ///< reason == kNone
  NotStillReason reason = NotStillReason::kTooShort;
  /// As DetectResult::quiet_level and ::threshold (the cap applied).
  double quiet_level = 0.0;
  double threshold = 0.0;
  /// The largest motion statistic of any window, and the time of that
  /// window's centre (kMoved: where the sensor moved most).
  double largest_statistic = 0.0;
  double largest_at_s = 0.0;
  /// kGap: the time before the gap; kRangeLimit: the time of the reading;
  /// kNotFinite: the time of the row before it.
  double gap_at_s = 0.0;
  std::size_t windows = 0;  ///< windows judged
  /// As DetectResult::window_samples and ::sample_period_s.
  std::size_t window_samples = 0;
  double sample_period_s = 0.0;
};

/// Decides, as the rows of a record arrive, whether the sensor was still
/// throughout, in memory that does not grow with the record (a window, a
/// few thousand buffered rows and at most 2^17 statistics): for a caller
/// that streams a long log and wants all of it only when it never moved.
///
/// The rule is DetectStatic's: the window is sized from the typical period
/// of the first 4096 rows; the motion statistic of every full window is the
/// one DetectStatic computes (the same sums, bit for bit, however the rows
/// are split); the quiet level is the `quiet_quantile` of a systematic
/// sample of the statistics (every s-th window, s doubling as the record
/// grows, so within a few percent of DetectStatic's exact quantile), at
/// least half the reading step; the threshold is `threshold_factor` times
/// it, capped at `max_still_g` as DetectStatic caps it. The record is still
/// when every window is at or below the threshold, no reading is at the
/// range limit (`range_mps2` given: 99 % of it in magnitude on any axis;
/// 0: 1.5 g on any axis, which a still sensor never reads), no time step is
/// longer than `window_s` (DetectStatic ends a still run there) and every
/// value is finite. Of the reasons found row by row (kNotFinite, kRangeLimit,
/// kGap) the first in time is reported; rows after a non-finite one are
/// ignored. A record in raw counts has no known g (neither cap nor range):
/// its rows are ignored and the verdict is kTooShort, no verdict.
class StillnessMonitor {
 public:
  /// \throws mpcal::Error if the options are invalid.
  StillnessMonitor(const DetectOptions& options, AccelUnits units);
  ~StillnessMonitor();
  StillnessMonitor(StillnessMonitor&&) noexcept;
  StillnessMonitor& operator=(StillnessMonitor&&) noexcept;
  StillnessMonitor(const StillnessMonitor&) = delete;
  StillnessMonitor& operator=(const StillnessMonitor&) = delete;

  /// Rows in time order (time strictly increasing across calls), split in
  /// any way; `time_s` and `accel` of the same length.
  /// \throws mpcal::Error if the lengths differ, time does not increase,
  ///   or the window is shorter than two samples (as DetectStatic).
  void Add(std::span<const double> time_s, std::span<const Eigen::Vector3d> accel);
  /// The verdict over all rows added so far (callable at the end, or at any
  /// time: windows not yet complete are not judged).
  /// \throws mpcal::Error if the window is shorter than two samples.
  StillVerdict Verdict() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// Each position grown to the motion on either side, for the turns between
/// them. Detection keeps a position's samples away from the motion by half
/// its window and the settling time (about 0.8 s at each end by default),
/// which the accelerometer's mean wants; a turn integrated by the gyroscope
/// over that still time only gathers its noise. A position's end moves
/// forward (and the next one's begin back) one sample at a time while the
/// mean over the next `kMotionEdgeWindowS` of each reading's departure from
/// the position's mean stays within the noise (χ² over the six axes of both
/// sensors, against the position's own scatter or the median position's
/// when larger, at 0.01 %); then it moves back by two such windows, since a
/// hand's turn starts as t² under the noise. Only `begin`, `end`, `start_s`
/// and `end_s` change: the means and scatters stay the detected ones. A
/// position never reaches past its neighbour's edge, and never shrinks.
/// Returns the intervals as given when the recording has no gyroscope.
std::vector<StaticInterval> ExtendToMotion(const RecordingView& recording,
                                           std::span<const StaticInterval> intervals);
/// ExtendToMotion's window (s): short beside a turn, long enough that a
/// slow start shows above the noise.
inline constexpr double kMotionEdgeWindowS = 0.05;

}  // namespace mpcal
