// Private to src/noise/: white noise through a first-order low-pass filter,
// for the term fit (noise_fit.cc AnalyseAxis): whether a curve's short end
// rolls off like one, and the filter's φ fitted with the other terms.
#pragma once

#include <cstddef>
#include <vector>

#include "mpcal/noise.h"
#include "noise/term_model.h"

namespace mpcal::internal::noise_fit {

/// Whether the curve's first k + 1 points look like a low-pass filter's
/// roll-off. The Allan deviation of white noise through a first-order
/// low-pass falls at every τ, its slope from about 0 steepening towards −½
/// and never beyond; a Gauss-Markov bump or a sinusoid on white noise
/// instead flattens or rises from −½ and falls steeper than −½ after its
/// peak. So: the first local slope flatter than −½, none steeper than −½,
/// and none flatter than a slope at a shorter τ, beyond its uncertainty (each point's
/// relative standard deviation from its interval, taken as independent: lenient).
bool ShortEndRollsOff(const std::vector<AllanPoint>& curve,
                      std::size_t k,
                      double confidence);

/// The low-pass filter's φ that best fits `curve` with the columns of `fit`
/// (the IEEE terms and the extra terms it has), by golden section with the
/// weights of `fit` held, then the coefficients refitted with reweighting at
/// it. Infinite cost when no φ fits. φ ranges over filters whose time
/// constant τ0/ln(1/φ) is at most the curve's first cluster time (the
/// short end cut off holds the roll-off): white noise through a slower
/// filter is a Gauss-Markov process, a bump, not a filter's roll-off.
Fit SearchLowpass(std::vector<AllanPoint>& curve,
                  const Fit& fit,
                  double tau0_s,
                  double phase_points,
                  const NoiseOptions& o);

}  // namespace mpcal::internal::noise_fit
