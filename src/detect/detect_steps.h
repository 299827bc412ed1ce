// The named steps of static detection (DetectStatic in detect.cc runs them
// in order): check and scan the samples, choose the window, find one g and
// the range limits, find the still runs, trim their settling, merge across
// bumps, build the intervals, and say why none was found.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "mpcal/detect.h"
#include "mpcal/recording.h"
#include "mpcal/recording_view.h"
#include "mpcal/sphere_fit.h"

namespace mpcal::internal {

/// Typical sample period (s) from (at most ~100k) consecutive differences:
/// the mean of those no longer than 1.5 x their median, so that a few gaps
/// do not move it, while timestamps rounded to the millisecond (a 160 Hz log
/// spaced 6, 6, 7, 6 ms) still give the true rate. Needs 2 samples or more.
double TypicalPeriod(std::span<const double> t);

/// Half the moving window in samples for the typical sample period
/// `period_s` (0: unknown): lround(window_s / period_s / 2), 1 at least, so
/// that the window of 2 half + 1 samples is centred on its sample. Throws
/// mpcal::Error when the window is shorter than two samples (it would
/// silently be three); `src` names the recording.
std::size_t HalfWindowFor(double window_s, double period_s, const std::string& src);

/// What detection needs from every sample, found in one pass over them.
struct SampleScan {
  /// The reading step of a quantised log (ADC counts, or values printed with
  /// few decimals): the smallest non-zero change between samples (checked at
  /// ~200k places spread over the log). 0 when the signal never changes.
  double resolution_step = 0.0;
  /// The extremes of each axis.
  Eigen::Vector3d highest = Eigen::Vector3d::Zero();
  Eigen::Vector3d lowest = Eigen::Vector3d::Zero();
};

/// Throws mpcal::Error unless every sample is finite and time strictly
/// increases, and scans the samples on the way. `src` names the recording.
SampleScan CheckAndScan(const RecordingView& recording, const std::string& src);

/// Mean of a[b, e), centred on a[b] so that counts near 32768 keep their
/// digits. Needs e > b.
Eigen::Vector3d MeanOf(std::span<const Eigen::Vector3d> a, std::size_t b, std::size_t e);

/// One g in the recording's units: fixed for g and m/s²; for counts the
/// radius of a sphere through the means of the still windows of `w` samples
/// (statistic `stat` at most `still_level`). Also the sphere's centre (0 for
/// g and m/s²), about which clipping limits are measured.
SphereFit GravityInUnits(const RecordingView& r,
                         const std::vector<double>& stat,
                         std::size_t w,
                         double still_level);

/// Samples at the sensor's range limit (see DetectOptions::range_mps2).
struct Clipping {
  std::vector<std::uint8_t> clipped;  ///< 1 per clipped sample
  std::size_t count = 0;
  /// The limits reached, e.g. "|x| >= 8.73773" or "z >= 32767".
  std::string limits;
};

/// Marks the samples at the range limit; `sphere` is one g and the zero in
/// the recording's units, `scan` has the readings' extremes.
Clipping MarkClipped(std::span<const Eigen::Vector3d> a,
                     double range_mps2,
                     const SphereFit& sphere,
                     const SampleScan& scan);

/// Runs [begin, end) of window centres in [first, last] whose statistic is
/// at most `threshold`. A time gap longer than `window_s` ends a run (the
/// statistic cannot see what happened in it).
struct StillRuns {
  std::vector<std::pair<std::size_t, std::size_t>> runs;
  std::size_t still_count = 0;  ///< still centres
};
StillRuns FindStillRuns(std::span<const double> t,
                        const std::vector<double>& stat,
                        std::size_t first,
                        std::size_t last,
                        double threshold,
                        double window_s);

/// A still stretch after trimming: kept samples [begin, end) and their mean.
struct Piece {
  std::size_t begin = 0;
  std::size_t end = 0;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
};

/// Trims `settle_s` of settling at both ends of each run; a run shorter than
/// twice that leaves nothing (a flicker below the threshold inside a turn).
/// `longest_still_s` gets the longest run before trimming.
std::vector<Piece> TrimSettling(std::span<const double> t,
                                std::span<const Eigen::Vector3d> a,
                                const StillRuns& runs,
                                double settle_s,
                                double* longest_still_s);

/// Groups neighbouring pieces at the same orientation (about `centre`, the
/// offset of the readings) across a short bump: the bump lasts less than
/// merge_gap_s once the trimmed settling on both sides, the window's smear
/// and stretches with no samples at all (dropped data) are taken out, and
/// the two means are within merge_angle_deg. `merged` counts the merges.
std::vector<std::vector<Piece>> MergeAcrossBumps(std::span<const double> t,
                                                 const std::vector<Piece>& pieces,
                                                 const Eigen::Vector3d& centre,
                                                 const DetectOptions& options,
                                                 int* merged);

/// The interval of a group of pieces: the span from the first to the last,
/// mean and std over the pieces' samples only (the bumps left out).
StaticInterval IntervalOf(const std::vector<Piece>& group,
                          std::span<const double> t,
                          std::span<const Eigen::Vector3d> a);

/// Why no interval was found (kFound when some were), with the figures and
/// the advice: `runs_found` says whether any window was still.
DetectFinding Diagnose(const DetectResult& result,
                       const DetectOptions& options,
                       double span_s,
                       bool runs_found,
                       const std::string& clip_limits);

}  // namespace mpcal::internal
