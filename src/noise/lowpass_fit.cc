// White noise through a first-order low-pass filter (lowpass_fit.h): the
// roll-off of a curve's short end told from a bump, and the filter's φ
// found by golden section with the other coefficients refitted.
#include "noise/lowpass_fit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "mpcal/noise.h"
#include "noise/term_model.h"

namespace mpcal::internal::noise_fit {

bool ShortEndRollsOff(const std::vector<AllanPoint>& curve,
                      std::size_t k,
                      double confidence) {
  const double z = std::sqrt(ChiSquareQuantile(confidence, 1.0));
  double steepest = std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < k && j + 1 < curve.size(); ++j) {
    const AllanPoint& a = curve[j];
    const AllanPoint& b = curve[j + 1];
    const double span = std::log(b.tau_s / a.tau_s);
    const double sd_a = std::log(a.adev_hi / a.adev_lo) / (2.0 * z);
    const double sd_b = std::log(b.adev_hi / b.adev_lo) / (2.0 * z);
    const double slope = std::log(b.adev / a.adev) / span;
    const double se = std::hypot(sd_a, sd_b) / span;
    if (slope < -0.5 - z * se || slope > steepest + z * se) return false;
    // The roll-off is strongest at the first cluster time: flatter than −½
    // there (a bump on white noise starts at −½).
    if (j == 0 && !(slope > -0.5 + z * se)) return false;
    steepest = std::min(steepest, slope);
  }
  return true;
}

Fit SearchLowpass(std::vector<AllanPoint>& curve,
                  const Fit& fit,
                  double tau0_s,
                  double phase_points,
                  const NoiseOptions& o) {
  TermMask allowed = kIeeeTerms & ~(1u << kQuantIndex), required = 0;
  for (const int col : {kGaussMarkov, kSinusoid}) {
    if (fit.m.c[col] > 0.0) allowed |= 1u << col, required |= 1u << col;
  }
  SetIntervals(curve, &fit.m, phase_points, o.allan.confidence);
  const std::vector<double> weight = ModelWeights(curve, fit.m);
  Model shape = fit.m;
  shape.tau0_s = tau0_s;
  const auto cost_at = [&](double phi) {
    Model m = shape;
    m.lowpass_phi = phi;
    return FitNonNegative(curve, weight, m, allowed, 0, required).cost;
  };
  const LineMinimum found =
      GoldenSection(cost_at, 0.0, std::exp(-tau0_s / curve.front().tau_s), 30);
  shape.lowpass_phi = found.at;
  if (!std::isfinite(found.cost)) return Fit{};
  return FitTerms(curve, allowed, phase_points, o, 0, shape, required, &fit.m);
}

}  // namespace mpcal::internal::noise_fit
