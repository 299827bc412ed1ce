// The overlapping Allan variance from cumulative sums, its equivalent degrees
// of freedom and χ² confidence intervals (see mpcal/noise.h for the method
// and the references).
#include <algorithm>
#include <array>
#include <bit>
#include <cassert>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "mpcal/error.h"
#include "mpcal/noise.h"
#include "noise/noise_fit.h"

namespace mpcal {
namespace {

// Rows per block of the fully overlapping kernel: the block and its two
// shifted copies (m ≤ full_overlap_max_m rows away) stay in the L2 cache
// while every small m is summed over them, so memory is read once for all
// of them instead of once per τ.
constexpr std::int64_t kBlockRows = 4096;

// The two kernels take nearly all the time of an analysis: built for AVX2
// as well as the baseline, the better one chosen at load time (GCC
// function multiversioning), so the portable build runs at the speed of a
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

// Regularised lower incomplete gamma P(a, x) (series below a + 1, Lentz's
// continued fraction above; Press et al., Numerical Recipes §6.2).
double RegularisedGammaP(double a, double x) {
  if (x <= 0.0) return 0.0;
  const double log_front = -x + a * std::log(x) - std::lgamma(a);
  if (x < a + 1.0) {
    double ap = a, del = 1.0 / a, sum = del;
    for (int n = 0; n < 100000 && std::abs(del) > std::abs(sum) * 1e-15; ++n) {
      ap += 1.0;
      del *= x / ap;
      sum += del;
    }
    return sum * std::exp(log_front);
  }
  constexpr double kTiny = 1e-300;
  double b = x + 1.0 - a, c = 1.0 / kTiny, d = 1.0 / b, h = d;
  for (int i = 1; i < 100000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::abs(del - 1.0) < 1e-15) break;
  }
  return 1.0 - std::exp(log_front) * h;
}

double NormalQuantile(double p) {
  double lo = -40.0, hi = 40.0;
  for (int i = 0; i < 200; ++i) {
    const double mid = 0.5 * (lo + hi);
    (0.5 * std::erfc(-mid / std::sqrt(2.0)) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

// Σ of the squared second differences of τ first..last-1, all of stride d,
// block by block (see OverlappingAllan).
void SumGroup(const double* theta,
              std::int64_t phase,
              const std::vector<std::int64_t>& ms,
              std::int64_t d,
              std::size_t first,
              std::size_t last,
              std::vector<std::array<long double, 3>>& totals) {
  const std::int64_t step = kBlockRows * d;
  for (std::int64_t k0 = 0; k0 < phase; k0 += step) {
    for (std::size_t j = first; j < last; ++j) {
      const std::int64_t k1 = std::min(k0 + step, phase - 2 * ms[j]);
      if (k1 <= k0) continue;
      if (d == 1) {
        SecondDifferenceSquares(theta, k0, k1, ms[j], totals[j].data());
      } else {
        StridedSecondDifferenceSquares(theta, k0, k1, ms[j], d, totals[j].data());
      }
    }
  }
}

}  // namespace

namespace internal {

std::int64_t ClusterStride(std::int64_t m, const AllanOptions& o) {
  return static_cast<std::int64_t>(std::bit_floor(
      static_cast<std::uint64_t>(std::max<std::int64_t>(1, m / o.min_overlaps))));
}

std::vector<std::int64_t> ClusterSizes(std::int64_t samples, const AllanOptions& o) {
  const auto m_max = static_cast<std::int64_t>(std::floor(o.max_tau_fraction * samples));
  std::vector<std::int64_t> ms;
  for (int j = 0;; ++j) {
    auto m = static_cast<std::int64_t>(std::llround(std::exp2(j / o.points_per_octave)));
    // A multiple of its stride (τ moves by under 1/(2 min_overlaps)), so
    // that the τ of one stride all start on the same grid of rows and are
    // summed together over blocks of it (OverlappingAllan).
    const std::int64_t d = ClusterStride(m, o);
    m = d * std::llround(static_cast<double>(m) / static_cast<double>(d));
    if (m > m_max) break;
    if (ms.empty() || m > ms.back()) ms.push_back(m);
  }
  return ms;
}

}  // namespace internal

std::string_view ToString(NoiseTerm term) {
  switch (term) {
    case NoiseTerm::kQuantisation:
      return "quantisation";
    case NoiseTerm::kWhiteNoise:
      return "white_noise";
    case NoiseTerm::kBiasInstability:
      return "bias_instability";
    case NoiseTerm::kRandomWalk:
      return "random_walk";
    case NoiseTerm::kRateRamp:
      return "rate_ramp";
  }
  return "?";
}

std::string AllanOptions::Validate() const {
  if (!(points_per_octave >= 1.0 && points_per_octave <= 64.0)) {
    return "points_per_octave must be in [1, 64]";
  }
  if (!(max_tau_fraction > 0.0 && max_tau_fraction <= 0.5)) {
    return "max_tau_fraction must be in (0, 0.5]";
  }
  if (min_overlaps < 1) return "min_overlaps must be at least 1";
  if (!(confidence > 0.0 && confidence < 1.0)) return "confidence must be in (0, 1)";
  return {};
}

CumulativeSums3 CumulativeSums3::FromSamples(std::vector<Eigen::Vector3d>&& samples,
                                             std::size_t begin,
                                             std::size_t end,
                                             double si_per_unit,
                                             double sample_period_s) {
  assert(begin < end && end <= samples.size() && sample_period_s > 0.0);
  // count samples give count + 1 sums; when the samples fill the vector the
  // last one is left out rather than grow it (which could double memory).
  const std::size_t count = end - begin - (end - begin + 1 > samples.size() ? 1 : 0);
  long double mean[3] = {};
  for (std::size_t i = begin; i < begin + count; ++i) {
    for (int j = 0; j < 3; ++j) mean[j] += samples[i][j];
  }
  for (long double& v : mean)
    v /= static_cast<long double>(std::max<std::size_t>(count, 1));

  // θ_k goes in slot k and y_{begin+k} is read from slot begin + k before
  // slot k is written (begin + k + 1 > k), so one forward pass works in place.
  CumulativeSums3 out;
  long double run[3] = {};
  Eigen::Vector3d next = samples[begin];
  for (std::size_t k = 0; k <= count; ++k) {
    const Eigen::Vector3d y = next;
    if (k + 1 < count) next = samples[begin + k + 1];
    for (int j = 0; j < 3; ++j) samples[k][j] = static_cast<double>(run[j] * si_per_unit);
    if (k < count) {
      for (int j = 0; j < 3; ++j) run[j] += y[j] - mean[j];
    }
  }
  // No shrink_to_fit: it would copy the whole vector to give back the spare
  // capacity, doubling memory for a moment.
  samples.resize(count + 1);
  out.theta_ = std::move(samples);
  out.sample_period_s_ = sample_period_s;
  out.mean_si_ = Eigen::Vector3d(static_cast<double>(mean[0] * si_per_unit),
                                 static_cast<double>(mean[1] * si_per_unit),
                                 static_cast<double>(mean[2] * si_per_unit));
  return out;
}

std::array<std::vector<AllanPoint>, 3> OverlappingAllan(const CumulativeSums3& sums,
                                                        const AllanOptions& options) {
  if (const std::string bad = options.Validate(); !bad.empty()) {
    throw Error(ErrorKind::kOption, "Allan options: " + bad);
  }
  const auto phase = static_cast<std::int64_t>(sums.size());
  if (phase < 9) {
    throw Error(ErrorKind::kInput,
                fmt::format("{} samples are too few for an Allan deviation (at least 8)",
                            std::max<std::int64_t>(phase - 1, 0)));
  }
  const std::vector<std::int64_t> ms = internal::ClusterSizes(phase - 1, options);
  const double* theta = sums.theta().front().data();
  std::vector<std::array<long double, 3>> totals(ms.size(), {0.0L, 0.0L, 0.0L});
  std::vector<std::int64_t> strides(ms.size(), 1);
  for (std::size_t j = 0; j < ms.size(); ++j) {
    strides[j] = internal::ClusterStride(ms[j], options);
  }
  // Fully overlapping τ (stride 1), block by block; then those of each
  // stride d together, over blocks of kBlockRows rows of the d-grid: their
  // m are multiples of d within a few dozen grid rows, so the rows a block
  // reads stay in cache for all of them and memory is read once per stride
  // rather than three scattered lines per term and τ.
  for (std::size_t first = 0; first < ms.size();) {
    std::size_t last = first;
    while (last < ms.size() && strides[last] == strides[first]) ++last;
    SumGroup(theta, phase, ms, strides[first], first, last, totals);
    first = last;
  }

  std::array<std::vector<AllanPoint>, 3> curves;
  for (std::size_t j = 0; j < ms.size(); ++j) {
    const std::int64_t m = ms[j];
    const std::int64_t terms = (phase - 2 * m - 1) / strides[j] + 1;
    for (int axis = 0; axis < 3; ++axis) {
      AllanPoint p;
      p.m = m;
      p.stride = strides[j];
      p.terms = terms;
      p.tau_s = static_cast<double>(m) * sums.sample_period_s();
      p.avar = static_cast<double>(totals[j][axis] /
                                   (2.0L * static_cast<long double>(m) * m * terms));
      p.adev = std::sqrt(p.avar);
      curves[axis].push_back(p);
    }
  }
  return curves;
}

double OverlappingAllanEdf(double n, double m, NoiseTerm dominant) {
  double edf = 0.0;
  switch (dominant) {
    case NoiseTerm::kQuantisation:  // white PM
      edf = (n + 1.0) * (n - 2.0 * m) / (2.0 * (n - m));
      break;
    case NoiseTerm::kWhiteNoise:  // white FM
      edf = (3.0 * (n - 1.0) / (2.0 * m) - 2.0 * (n - 2.0) / n) * 4.0 * m * m /
            (4.0 * m * m + 5.0);
      break;
    case NoiseTerm::kBiasInstability:  // flicker FM
      edf = m == 1.0 ? 2.0 * (n - 2.0) * (n - 2.0) / (2.3 * n - 4.9)
                     : 5.0 * n * n / (4.0 * m * (n + 3.0 * m));
      break;
    case NoiseTerm::kRandomWalk:  // random-walk FM
    case NoiseTerm::kRateRamp:
      edf = (n - 2.0) / m * ((n - 1.0) * (n - 1.0) - 3.0 * m * (n - 1.0) + 4.0 * m * m) /
            ((n - 3.0) * (n - 3.0));
      break;
  }
  return std::max(edf, 1.0);
}

double ChiSquareQuantile(double p, double dof) {
  assert(p > 0.0 && p < 1.0 && dof > 0.0);
  if (dof > 2000.0) {  // Wilson & Hilferty (1931), relative error < 1e-5 here
    const double h = 2.0 / (9.0 * dof);
    return dof * std::pow(1.0 - h + NormalQuantile(p) * std::sqrt(h), 3);
  }
  const double a = 0.5 * dof;
  double lo = 0.0, hi = std::max(1.0, dof);
  while (RegularisedGammaP(a, 0.5 * hi) < p) hi *= 2.0;
  for (int i = 0; i < 200 && hi - lo > 1e-13 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (RegularisedGammaP(a, 0.5 * mid) < p ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace mpcal
