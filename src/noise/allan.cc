// The cluster sizes of the overlapping Allan variance, its equivalent
// degrees of freedom and χ² confidence intervals (see mpcal/noise.h for the
// method and the references; the sums themselves are in allan_sums.cc).
#include <algorithm>
#include <bit>
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
    // summed together over blocks of it (AllanSums).
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
