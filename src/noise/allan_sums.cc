// The overlapping Allan variance summed as the samples arrive (AllanSums,
// see mpcal/noise.h): the kernels of the squared second differences, the
// cluster sizes summed on the way and those summed from the kept sums at the
// end.
#include <algorithm>
#include <array>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "mpcal/error.h"
#include "mpcal/noise.h"
#include "noise/noise_fit.h"

namespace mpcal {
namespace {

// Samples turned into sums before the near cluster sizes are summed over
// them: the new sums and the history before them stay in the L2 cache
// while every near m reads them.
constexpr std::size_t kAddBlock = 8192;

// Rows per block of the far sums: the block and its two shifted copies stay
// in cache while every m of one stride is summed over them.
constexpr std::int64_t kFarBlockRows = 4096;

// The two kernels take most of the time of an analysis: built for AVX2 as
// well as the baseline, the better one chosen at load time (GCC function
// multiversioning), so the portable build runs at the speed of a
// -march=native one.
#if defined(__GNUC__) && defined(__x86_64__) && !defined(__clang__)
#define MPCAL_VECTOR_CLONES __attribute__((target_clones("avx2", "default")))
#else
#define MPCAL_VECTOR_CLONES
#endif

// Σ_{k ∈ [k0, k1)} (θ_{k+2m} − 2θ_{k+m} + θ_k)² per axis, θ as 3 doubles a
// row. Twelve partial sums (four rows of three axes) let the compiler keep
// them in vector registers; the axis of lane j is j mod 3.
MPCAL_VECTOR_CLONES void SecondDifferenceSquares(const double* theta,
                                                 std::int64_t k0,
                                                 std::int64_t k1,
                                                 std::int64_t m,
                                                 long double out[3]) {
  const double* a = theta + 3 * k0;
  const double* b = a + 3 * m;
  const double* c = a + 6 * m;
  const std::int64_t n = 3 * (k1 - k0);
  double acc[12] = {};
  std::int64_t i = 0;
  for (; i + 12 <= n; i += 12) {
    for (int j = 0; j < 12; ++j) {
      const double v = c[i + j] - 2.0 * b[i + j] + a[i + j];
      acc[j] += v * v;
    }
  }
  for (; i < n; ++i) {
    const double v = c[i] - 2.0 * b[i] + a[i];
    acc[i % 3] += v * v;
  }
  for (int j = 0; j < 12; ++j) out[j % 3] += acc[j];
}

// The same over start indices k0, k0 + d, k0 + 2d, ... < k1.
MPCAL_VECTOR_CLONES void StridedSecondDifferenceSquares(const double* theta,
                                                        std::int64_t k0,
                                                        std::int64_t k1,
                                                        std::int64_t m,
                                                        std::int64_t d,
                                                        long double out[3]) {
  double acc[3] = {};
  for (std::int64_t k = k0; k < k1; k += d) {
    const double* a = theta + 3 * k;
    const double* b = a + 3 * m;
    const double* c = a + 6 * m;
    for (int j = 0; j < 3; ++j) {
      const double v = c[j] - 2.0 * b[j] + a[j];
      acc[j] += v * v;
    }
  }
  for (int j = 0; j < 3; ++j) out[j] += acc[j];
}

void SumStarts(const double* theta,
               std::int64_t k0,
               std::int64_t k1,
               std::int64_t m,
               std::int64_t d,
               long double out[3]) {
  if (d == 1) {
    SecondDifferenceSquares(theta, k0, k1, m, out);
  } else {
    StridedSecondDifferenceSquares(theta, k0, k1, m, d, out);
  }
}

// The far cluster sizes ms[first, last), all of stride d, over the kept sums
// (`rows` of them, kFarStride samples apart), block by block.
void SumFar(const std::vector<double>& far,
            const std::vector<std::int64_t>& ms,
            std::int64_t d,
            std::size_t first,
            std::size_t last,
            std::vector<std::array<long double, 3>>& totals) {
  const auto rows = static_cast<std::int64_t>(far.size() / 3);
  const std::int64_t step = d / AllanSums::kFarStride;
  for (std::int64_t k0 = 0; k0 < rows; k0 += kFarBlockRows * step) {
    for (std::size_t j = first; j < last; ++j) {
      const std::int64_t m = ms[j] / AllanSums::kFarStride;
      const std::int64_t k1 = std::min(k0 + kFarBlockRows * step, rows - 2 * m);
      if (k1 > k0) SumStarts(far.data(), k0, k1, m, step, totals[j].data());
    }
  }
}

}  // namespace

AllanSums::AllanSums(const AllanOptions& options) : options_(options) {
  if (const std::string bad = options.Validate(); !bad.empty()) {
    throw Error(ErrorKind::kOption, "Allan options: " + bad);
  }
  // Every near cluster size a record can have: those of a record too long
  // to end the list before the strides reach kFarStride.
  for (const std::int64_t m : internal::ClusterSizes(std::int64_t{1} << 60, options)) {
    const std::int64_t d = internal::ClusterStride(m, options);
    if (d >= kFarStride) break;
    near_.push_back(Near{m, d, 0, {}});
    history_ = 2 * m;
  }
  recent_.assign(3, 0.0);  // θ_0
  far_.assign(3, 0.0);
}

// Distinct values (up to 3) and the smallest change of each axis: a stuck,
// toggling or coarsely quantised axis is told from noise by these. Axis by
// axis, in registers: once three values are seen only the smallest change
// is left to follow.
void AllanSums::TrackValues(const Eigen::Vector3d* samples, std::size_t count) {
  if (count == 0) return;
  std::size_t from = 0;
  if (samples_ == 0) {
    for (int j = 0; j < 3; ++j) {
      distinct_[j] = 1;
      values_[j][0] = previous_[j] = samples[0][j];
    }
    from = 1;
  }
  for (int j = 0; j < 3; ++j) {
    double previous = previous_[j];
    double resolution = resolution_[j];  // 0: no change yet
    std::size_t i = from;
    for (; i < count && distinct_[j] < 3; ++i) {
      const double v = samples[i][j];
      const double change = std::abs(v - previous);
      if (change > 0.0 && (resolution == 0.0 || change < resolution)) resolution = change;
      if (v != values_[j][0] && (distinct_[j] < 2 || v != values_[j][1])) {
        if (distinct_[j] < 2) values_[j][1] = v;
        ++distinct_[j];
      }
      previous = v;
    }
    for (; i < count; ++i) {
      const double v = samples[i][j];
      const double change = std::abs(v - previous);
      if (change > 0.0 && (resolution == 0.0 || change < resolution)) resolution = change;
      previous = v;
    }
    previous_[j] = previous;
    resolution_[j] = resolution;
  }
}

AllanSums::AxisValues AllanSums::Values(int axis) const {
  assert(axis >= 0 && axis < 3);
  AxisValues v;
  v.distinct = distinct_[axis];
  v.first = values_[axis][0];
  v.resolution = resolution_[axis];
  // The first near cluster size is m = 1: its squared second differences of
  // θ are the squared steps of the samples.
  if (!near_.empty() && near_.front().m == 1 && samples_ > 1) {
    v.adev_tau0 = std::sqrt(static_cast<double>(
        near_.front().total[axis] / (2.0L * static_cast<long double>(samples_ - 1))));
  }
  return v;
}

void AllanSums::Add(const Eigen::Vector3d* samples, std::size_t count) {
  TrackValues(samples, count);
  if (count > 0 && samples_ == 0) first_ = samples[0];
  // The running sums and the count in locals, the block's sums written in
  // place: stores into recent_ would otherwise make the compiler reload
  // them for every sample.
  const Eigen::Vector3d first = first_;
  std::array<long double, 3> run = run_;
  for (std::size_t done = 0; done < count;) {
    const std::size_t block = std::min(kAddBlock, count - done);
    const std::size_t at = recent_.size();
    recent_.resize(at + 3 * block);
    double* const sums = recent_.data() + at;
    std::size_t n = samples_;
    for (std::size_t i = 0; i < block; ++i) {
      const Eigen::Vector3d& x = samples[done + i];
      double* const theta = sums + 3 * i;
      for (int j = 0; j < 3; ++j) {
        run[j] += x[j] - first[j];
        theta[j] = static_cast<double>(run[j]);
      }
      if (++n % kFarStride == 0) far_.insert(far_.end(), theta, theta + 3);
    }
    samples_ = n;
    run_ = run;
    done += block;
    SumNear();
  }
}

// The near cluster sizes over the start indices whose last sum has come,
// then the sums no start will read again are dropped.
void AllanSums::SumNear() {
  const auto last = static_cast<std::int64_t>(samples_);  // index of the newest sum
  for (Near& near : near_) {
    const std::int64_t k1 = last - 2 * near.m + 1;
    if (k1 <= near.next_start) continue;
    assert(near.next_start >= base_);
    SumStarts(recent_.data(),
              near.next_start - base_,
              k1 - base_,
              near.m,
              near.stride,
              near.total.data());
    near.next_start +=
        (k1 - near.next_start + near.stride - 1) / near.stride * near.stride;
  }
  const std::int64_t keep_from = std::max<std::int64_t>(base_, last - history_);
  recent_.erase(recent_.begin(), recent_.begin() + 3 * (keep_from - base_));
  base_ = keep_from;
}

Eigen::Vector3d AllanSums::Mean() const {
  if (samples_ == 0) return Eigen::Vector3d::Zero();
  const auto n = static_cast<long double>(samples_);
  return first_ + Eigen::Vector3d(static_cast<double>(run_[0] / n),
                                  static_cast<double>(run_[1] / n),
                                  static_cast<double>(run_[2] / n));
}

std::array<std::vector<AllanPoint>, 3> AllanSums::Curves(double si_per_unit,
                                                         double sample_period_s) const {
  const auto phase = static_cast<std::int64_t>(samples_) + 1;
  if (phase < 9) {
    throw Error(ErrorKind::kInput,
                fmt::format("{} samples are too few for an Allan deviation (at least 8)",
                            samples_));
  }
  const std::vector<std::int64_t> ms = internal::ClusterSizes(phase - 1, options_);
  std::vector<std::array<long double, 3>> totals(ms.size(), {0.0L, 0.0L, 0.0L});
  std::vector<std::int64_t> strides(ms.size());
  for (std::size_t j = 0; j < ms.size(); ++j) {
    strides[j] = internal::ClusterStride(ms[j], options_);
    if (j < near_.size()) totals[j] = near_[j].total;
  }
  for (std::size_t first = near_.size(); first < ms.size();) {
    std::size_t last = first;
    while (last < ms.size() && strides[last] == strides[first]) ++last;
    SumFar(far_, ms, strides[first], first, last, totals);
    first = last;
  }

  std::array<std::vector<AllanPoint>, 3> curves;
  const long double si2 = static_cast<long double>(si_per_unit) * si_per_unit;
  for (std::size_t j = 0; j < ms.size(); ++j) {
    const std::int64_t m = ms[j];
    const std::int64_t terms = (phase - 2 * m - 1) / strides[j] + 1;
    for (int axis = 0; axis < 3; ++axis) {
      AllanPoint p;
      p.m = m;
      p.stride = strides[j];
      p.terms = terms;
      p.tau_s = static_cast<double>(m) * sample_period_s;
      p.avar = static_cast<double>(totals[j][axis] * si2 /
                                   (2.0L * static_cast<long double>(m) * m * terms));
      p.adev = std::sqrt(p.avar);
      curves[axis].push_back(p);
    }
  }
  return curves;
}

}  // namespace mpcal
