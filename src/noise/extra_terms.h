// Private to src/noise/: the terms beyond the IEEE five, a Gauss-Markov
// process and a sinusoid, for the term fit (noise_fit.cc AnalyseAxis): where
// the curve shows them, and what it says of them.
#pragma once

#include <vector>

#include "mpcal/noise.h"
#include "noise/term_model.h"

namespace mpcal::internal::noise_fit {

/// The extra terms the curve shows, added to the IEEE fit `base` one at a
/// time while the Bayesian information criterion (Schwarz 1978) falls: each
/// adds two parameters (its coefficient and its τc or P), and is kept when
/// Pearson's statistic falls by more than 2 ln n_eff, both counted in
/// independent points (the statistic and n divided by the same correlation
/// factor as the covariance, NoiseOptions::independent_points_per_octave),
/// and its coefficient is above zero by its interval. The bump's peak must
/// lie an octave and a half beyond the curve's first cluster time
/// (`first_tau_s`: a low-pass filter's roll-off, itself a Gauss-Markov
/// process of τc = 1/(2πF), is not a bump) and four octaves before its last
/// (its falling side seen); a sinusoid's anywhere from the second cluster
/// time to four octaves before the last.
Fit AddExtraTerms(std::vector<AllanPoint>& curve,
                  const Fit& base,
                  TermMask signed_terms,
                  double first_tau_s,
                  double phase_points,
                  const NoiseOptions& o);

/// The Gauss-Markov process and the sinusoid in the fitted model: value,
/// interval, τc or P with the range the curve allows, and region.
void MeasureExtraTerms(const std::vector<AllanPoint>& curve,
                       const Fit& fit,
                       TermMask signed_terms,
                       const NoiseOptions& o,
                       AxisNoise& out);

}  // namespace mpcal::internal::noise_fit
