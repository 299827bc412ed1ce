#include "mpcal/gap_counter.h"

#include <algorithm>
#include <cstddef>
#include <vector>

namespace mpcal {

void GapCounter::Add(std::span<const double> times_s) {
  std::size_t i = 0;
  while (!settled_ && i < times_s.size()) {
    early_.push_back(times_s[i++]);
    if (early_.size() > reference_steps_) Settle();
  }
  if (i == times_s.size()) return;
  double before = last_;
  for (; i < times_s.size(); ++i) {
    Step(before, times_s[i]);
    before = times_s[i];
  }
  last_ = before;
}

void GapCounter::Finish() {
  if (!settled_) Settle();
}

// The typical step from the times held, then their steps counted.
void GapCounter::Settle() {
  settled_ = true;
  if (early_.size() < 3) return;  // too few steps to call one typical
  std::vector<double> steps;
  steps.reserve(early_.size() - 1);
  for (std::size_t i = 0; i + 1 < early_.size(); ++i) {
    steps.push_back(early_[i + 1] - early_[i]);
  }
  const auto middle = steps.begin() + static_cast<std::ptrdiff_t>(steps.size() / 2);
  std::nth_element(steps.begin(), middle, steps.end());
  typical_ = *middle;
  limit_ = factor_ * typical_;
  for (std::size_t i = 0; i + 1 < early_.size(); ++i) Step(early_[i], early_[i + 1]);
  last_ = early_.back();
  std::vector<double>().swap(early_);
}

}  // namespace mpcal
