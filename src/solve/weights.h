// Standard deviation of one position's residual |a_k| − g, propagated from
// the noise of its mean reading. Weighting the scalar residual by it makes
// the estimator the first-order maximum-likelihood one for the full model
// with each position's direction as a nuisance (the Sampson distance), which
// is what lets it reach the Cramér-Rao bound (cramer_rao.h).
#pragma once

#include <span>

#include <Eigen/Core>

#include "mpcal/model.h"
#include "mpcal/solve.h"

namespace mpcal::internal {

/// Per-axis noise of each position's readings (m/s²), made safe to divide
/// by: an axis whose readings never changed (a quiet sensor read in coarse
/// counts) gets the typical level of the other positions instead of zero.
std::vector<Eigen::Vector3d> UsableNoise(std::span<const PositionObservation> positions);

/// σ of |a| − g at `model` for a mean reading with per-axis noise
/// `noise_mps2` over `samples` samples (m/s²).
double ResidualSigma(const ErrorModel& model,
                     const Eigen::Vector3d& mean_mps2,
                     const Eigen::Vector3d& noise_mps2,
                     std::size_t samples);

/// Median of the χ² distribution with one degree of freedom.
inline constexpr double kChiSquare1Median = 0.454936;

/// The value the sample median of `count` independent χ²₁ variables (the
/// element of rank count/2 from zero, as std::nth_element picks it) exceeds
/// with probability `alpha`: exact, from the binomial count of values below
/// it.
double ChiSquare1MedianQuantile(std::size_t count, double alpha);

/// The variance τ² (m/s²)² of a scatter of the positions that their sensor
/// noise does not explain — hand tremor, non-white noise, model error —
/// added to every position's variance: σ_k² + τ². A variance component
/// (Förstner 1979) estimated robustly, so that one bumped position cannot
/// inflate it and hide itself: the median of r_k²/((σ_k² + τ²)(1 − h_k)),
/// h_k the position's leverage, is matched to that of χ²₁; or, when it is
/// smaller, the estimate that matches their mean to 1 (a median high by
/// chance must not inflate it either).
///
/// Estimated only on evidence, by a test at 1 %: the median of the
/// standardised squares r_k²/(σ_k²(1 − h_k)) must exceed what the median of
/// K independent χ²₁ values exceeds once in 100 sessions of white noise
/// (ChiSquare1MedianQuantile). The median, not the χ² sum, so that one
/// outlier cannot pass the test for the rest; the exact quantile, so that
/// the test holds at any number of positions (at least
/// kMinScatterRedundancy redundant ones). Zero otherwise: white-noise
/// sessions keep their efficient weights.
double PositionScatterVariance(const std::vector<double>& residuals_mps2,
                               const std::vector<double>& sigmas_mps2,
                               const std::vector<double>& leverages);

/// Fewer redundant positions (K − p) than this never show a scatter: the
/// median of so few residuals says too little.
inline constexpr int kMinScatterRedundancy = 5;
/// Significance of the scatter test.
inline constexpr double kScatterSignificance = 0.01;

}  // namespace mpcal::internal
