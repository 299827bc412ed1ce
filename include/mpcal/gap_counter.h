/// \file gap_counter.h
/// \brief Gaps in a record's time, counted as its times arrive.
#pragma once

#include <cstddef>
#include <span>
#include <vector>

namespace mpcal {

/// Steps longer than `factor` typical ones, the typical step being the
/// median of the first `reference_steps` steps (the times held until there
/// are that many, or until Finish): the rule needs neither the whole record
/// nor its length, so a record counted whole or in pieces gives the same
/// figures. Fewer than 2 steps in all: no typical step and no gap.
class GapCounter {
 public:
  GapCounter(std::size_t reference_steps, double factor)
      : reference_steps_(reference_steps), factor_(factor) {}
  /// The next times (strictly increasing, after those added before).
  void Add(std::span<const double> times_s);
  /// Counts the steps still held, once every time was added.
  void Finish();

  /// After Finish: the gaps, the typical step, the largest gap and the time
  /// before it (0 without a gap).
  std::size_t gaps() const { return gaps_; }
  double typical_s() const { return typical_; }
  double largest_s() const { return largest_; }
  double largest_at_s() const { return largest_at_; }

 private:
  void Settle();
  void Step(double before, double after) {
    const double step = after - before;
    if (step <= limit_) return;
    ++gaps_;
    if (step > largest_) {
      largest_ = step;
      largest_at_ = before;
    }
  }

  std::size_t reference_steps_;
  double factor_;
  std::vector<double> early_;  // the first times, until the typical step is known
  bool settled_ = false;
  double last_ = 0.0;  // the last time added, once settled
  double typical_ = 0.0;
  double limit_ = 0.0;
  std::size_t gaps_ = 0;
  double largest_ = 0.0;
  double largest_at_ = 0.0;
};

}  // namespace mpcal
