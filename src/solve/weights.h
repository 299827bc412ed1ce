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
double ResidualSigma(const ErrorModel& model, const Eigen::Vector3d& mean_mps2,
                     const Eigen::Vector3d& noise_mps2, std::size_t samples);

/// The variance τ² (m/s²)² of a scatter of the positions that their sensor
/// noise does not explain — hand tremor, non-white noise, model error —
/// added to every position's variance: σ_k² + τ². A variance component
/// (Förstner 1979) estimated robustly, so that one bumped position cannot
/// inflate it and hide itself: the median of r_k²/(σ_k² + τ²) is matched to
/// that of χ²₁ (scaled by (K − p)/K for the fitted parameters). Zero unless
/// the residuals show more scatter than the noise explains by ten times the
/// sampling spread of that median, so that white-noise sessions keep their
/// efficient weights, and zero with fewer than 10 redundant positions
/// (K − p < 10), whose median is too uncertain to tell.
double PositionScatterVariance(const std::vector<double>& residuals_mps2,
                               const std::vector<double>& sigmas_mps2, int parameters);

}  // namespace mpcal::internal
