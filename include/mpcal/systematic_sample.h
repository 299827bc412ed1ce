/// \file systematic_sample.h
/// \brief A sample of bounded size from a stream of values too long to
/// hold (the steps of an 8-hour log, the magnitudes of its readings), from
/// which its quantiles are taken.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace mpcal {

/// Every s-th value of a stream, by its index in the stream, s a power of
/// two that doubles (every other kept value dropped) whenever more than
/// `capacity` are kept. So the values kept do not depend on how the stream
/// was split, and memory stays at `capacity` values; a quantile of them is
/// the stream's within a few 1/√capacity in rank.
class SystematicSample {
 public:
  explicit SystematicSample(std::size_t capacity = std::size_t{1} << 16)
      : capacity_(std::max<std::size_t>(capacity, 2)) {}

  void Add(double value) {
    if ((index_++ & (stride_ - 1)) != 0) return;
    kept_.push_back(value);
    if (kept_.size() <= capacity_) return;
    std::size_t out = 0;
    for (std::size_t i = 0; i < kept_.size(); i += 2) kept_[out++] = kept_[i];
    kept_.resize(out);
    stride_ *= 2;
  }
  /// Values seen, and those kept.
  std::uint64_t seen() const { return index_; }
  const std::vector<double>& kept() const { return kept_; }
  /// The value below which a fraction q of the kept values lies (nearest
  /// rank, the lower of two); 0 when none was added.
  double Quantile(double q) const {
    if (kept_.empty()) return 0.0;
    std::vector<double> v = kept_;
    const auto k = static_cast<std::size_t>(std::clamp(q, 0.0, 1.0) *
                                            static_cast<double>(v.size() - 1));
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
    return v[k];
  }

 private:
  std::size_t capacity_;
  std::uint64_t stride_ = 1;
  std::uint64_t index_ = 0;
  std::vector<double> kept_;
};

}  // namespace mpcal
