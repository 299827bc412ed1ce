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
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mpcal/recording.h"

namespace mpcal {

struct DetectOptions {
  /// Length of the moving window of the motion statistic (s). Longer rejects
  /// slow drifts of the hand better, shorter resolves short positions.
  double window_s = 1.0;
  /// Shortest static interval kept, after trimming (s).
  double min_static_s = 2.0;
  /// Trimmed from each end of an interval to drop settling (s).
  double settle_s = 0.3;
  /// Threshold = this factor × the quiet level of the recording.
  double threshold_factor = 3.0;
  /// Intervals closer than this in time (s) and in orientation (deg) merge.
  double merge_gap_s = 1.0;
  double merge_angle_deg = 3.0;

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
  /// recording's units.
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  Eigen::Vector3d std = Eigen::Vector3d::Zero();
  std::size_t samples() const { return end - begin; }
  double duration_s() const { return end_s - start_s; }
};

struct DetectResult {
  std::vector<StaticInterval> intervals;
  /// Quiet level of the motion statistic and the threshold used (recording
  /// units).
  double quiet_level = 0.0;
  double threshold = 0.0;
  /// Still stretches dropped for being shorter than min_static_s.
  int dropped_short = 0;
  /// Pairs of intervals merged across a short bump.
  int merged = 0;
};

/// \throws mpcal::Error if the recording is empty or too short for one
///   window, or the options are invalid.
DetectResult DetectStatic(const Recording& recording, const DetectOptions& options);

}  // namespace mpcal
