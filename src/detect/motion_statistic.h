// The motion statistic of static detection and the quantiles taken of it:
// templates, so that the per-sample visits inline into their callers (a
// recording has millions of samples).
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include <Eigen/Core>

namespace mpcal::internal {

// The value below which a fraction q of `values` lies (nearest rank).
inline double Quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  const auto k =
      static_cast<std::size_t>(std::clamp(q * static_cast<double>(values.size() - 1),
                                          0.0,
                                          static_cast<double>(values.size() - 1)));
  std::nth_element(
      values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

// Quantile (as Quantile: nearest rank, exactly) of `count` values that
// `for_each_value(f)` visits again, calling f(value) for each, from a
// strided sample of them (every `stride`th; all when `stride` is 1): the
// sample brackets the rank, and a visit keeps only the values inside the
// bracket, so that millions of values are neither copied nor selected among.
// Visits again, keeping all, when the bracket misses (or a value is NaN).
template <typename ForEachValue>
double QuantileOf(std::vector<double> sample,
                  std::size_t stride,
                  std::size_t count,
                  double q,
                  ForEachValue&& for_each_value) {
  auto keep_all = [&] {
    std::vector<double> all;
    all.reserve(count);
    for_each_value([&](double v) { all.push_back(v); });
    return Quantile(std::move(all), q);
  };
  if (stride <= 1) return Quantile(std::move(sample), q);
  if (sample.empty() || count == 0) return keep_all();
  const auto rank = static_cast<std::size_t>(std::clamp(
      q * static_cast<double>(count - 1), 0.0, static_cast<double>(count - 1)));
  // The sample's rank of q, +- 5 standard deviations of a sampled rank.
  const double m = static_cast<double>(sample.size());
  const double centre = q * (m - 1.0);
  const double margin = 5.0 * std::sqrt(m * std::clamp(q * (1.0 - q), 1e-6, 0.25)) + 16.0;
  auto sample_at = [&](double r) {
    const auto k = static_cast<std::ptrdiff_t>(r);
    std::nth_element(sample.begin(), sample.begin() + k, sample.end());
    return sample[static_cast<std::size_t>(k)];
  };
  const double lo = centre - margin < 0.0 ? -std::numeric_limits<double>::infinity()
                                          : sample_at(centre - margin);
  const double hi = centre + margin > m - 1.0 ? std::numeric_limits<double>::infinity()
                                              : sample_at(centre + margin);
  std::size_t below = 0;
  bool nan = false;
  std::vector<double> inside;
  inside.reserve(4 * static_cast<std::size_t>(margin) * stride);
  for_each_value([&](double v) {
    if (v < lo) {
      ++below;
    } else if (v <= hi) {
      inside.push_back(v);
    } else {
      nan |= std::isnan(v);
    }
  });
  if (nan || rank < below || rank >= below + inside.size()) return keep_all();
  const auto k = static_cast<std::ptrdiff_t>(rank - below);
  std::nth_element(inside.begin(), inside.begin() + k, inside.end());
  return inside[static_cast<std::size_t>(k)];
}

// The running sums of ForEachWindow, carried from one stretch of readings to
// the next so that a record fed in pieces gives the statistic of every
// window bit for bit as in one piece.
struct WindowSums {
  Eigen::Vector3d s1 = Eigen::Vector3d::Zero();
  Eigen::Vector3d s2 = Eigen::Vector3d::Zero();
  // Windows until the sums are redone from scratch (0: the next one is).
  std::size_t until_resync = 0;
};

// How often ForEachWindow redoes its sums (windows), for a window of w.
inline std::size_t ResyncWindows(std::size_t w) {
  return std::max<std::size_t>(4096, 8 * w);
}

// The motion statistic of the window of 2 half + 1 readings centred on each
// a[c], c in [first, a.size() - 1 - half], in order: visit(c, statistic). By
// sliding sums (`sums`, carried over and updated) over readings centred on
// `ref` (the record's first reading: counts near 32768 would otherwise lose
// their noise to cancellation). The sums are redone from scratch every
// ResyncWindows(w) windows so that rounding cannot build up over millions of
// samples. Unless `sums` are due to be redone, they must hold the window
// centred on first - 1, and first > half (the reading leaving is read).
template <typename Visit>
void ForEachWindow(std::span<const Eigen::Vector3d> a,
                   std::size_t half,
                   std::size_t first,
                   const Eigen::Vector3d& ref_reading,
                   WindowSums* sums,
                   Visit&& visit) {
  const std::size_t n = a.size();
  if (n < first + half + 1) return;
  const std::size_t w = 2 * half + 1;
  // A copy, not a reference: read for every sample, kept in registers.
  // NOLINTNEXTLINE(performance-unnecessary-copy-initialization)
  const Eigen::Vector3d ref = ref_reading;
  const std::size_t last = n - 1 - half;  // inclusive
  const std::size_t resync = ResyncWindows(w);
  Eigen::Vector3d s1 = sums->s1;
  Eigen::Vector3d s2 = sums->s2;
  // Multiplications: six divisions per sample were a third of detection.
  const double inv_w = 1.0 / static_cast<double>(w);
  const double inv_w1 = 1.0 / static_cast<double>(w - 1);
  std::size_t until_resync = sums->until_resync;
  for (std::size_t c = first; c <= last; ++c) {
    const std::size_t lo = c - half;
    const std::size_t hi = c + half;  // inclusive
    if (until_resync-- == 0) {
      until_resync = resync - 1;
      s1.setZero();
      s2.setZero();
      for (std::size_t j = lo; j <= hi; ++j) {
        const Eigen::Vector3d d = a[j] - ref;
        s1 += d;
        s2 += d.cwiseAbs2();
      }
    } else {
      const Eigen::Vector3d add = a[hi] - ref;
      const Eigen::Vector3d sub = a[lo - 1] - ref;
      s1 += add - sub;
      s2 += add.cwiseAbs2() - sub.cwiseAbs2();
    }
    const Eigen::Vector3d var = ((s2 - s1.cwiseAbs2() * inv_w) * inv_w1).cwiseMax(0.0);
    visit(c, std::sqrt(var.sum()));
  }
  sums->s1 = s1;
  sums->s2 = s2;
  sums->until_resync = until_resync;
}

// The motion statistic of every window of a whole record, centred on each
// sample c in [half, n - 1 - half], in order: visit(c, statistic).
template <typename Visit>
void ForEachWindow(std::span<const Eigen::Vector3d> a, std::size_t half, Visit&& visit) {
  if (a.empty()) return;
  WindowSums sums;
  ForEachWindow(a, half, half, a[0], &sums, std::forward<Visit>(visit));
}

}  // namespace mpcal::internal
