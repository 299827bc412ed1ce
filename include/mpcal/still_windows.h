/// \file still_windows.h
/// \brief Static detection's motion statistic, window by window as the rows
/// arrive, and the threshold of the windows so far: StillnessMonitor's rule
/// (detect.h) for a caller that shows stillness live (record_guide.h).
#pragma once

#include <cstddef>
#include <memory>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "mpcal/detect.h"
#include "mpcal/units.h"

namespace mpcal {

/// One window as it is judged: its centre (the row's index from the first
/// row added, its time and reading) and its motion statistic.
struct StillWindow {
  std::size_t row = 0;
  double centre_s = 0.0;
  Eigen::Vector3d reading = Eigen::Vector3d::Zero();
  double statistic = 0.0;
};

/// StillnessMonitor's state and rule (the same sums, window, quiet level and
/// threshold; detect.h), with every window handed over as it is judged, and
/// the window sized from the first `period_rows` rows instead of 4096: a
/// live caller sizes it from a few seconds of rows.
class StillWindows {
 public:
  /// \throws mpcal::Error if the options are invalid.
  StillWindows(const DetectOptions& options, AccelUnits units, std::size_t period_rows);
  ~StillWindows();
  StillWindows(StillWindows&&) noexcept;
  StillWindows& operator=(StillWindows&&) noexcept;
  StillWindows(const StillWindows&) = delete;
  StillWindows& operator=(const StillWindows&) = delete;

  /// As StillnessMonitor::Add, appending every window these rows complete
  /// to `judged`, in order (the same windows however the rows are split).
  void Add(std::span<const double> time_s,
           std::span<const Eigen::Vector3d> accel,
           std::vector<StillWindow>* judged);
  /// As StillnessMonitor::Verdict: its threshold is the one of the windows
  /// so far.
  StillVerdict Verdict() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

}  // namespace mpcal
