/// \file cramer_rao.h
/// \brief The Cramér-Rao bound of the multi-position calibration, the
/// accuracy limit no unbiased estimator beats (docs/method.md §3.8).
///
/// Model: Ȳ_k = Forward(θ, g·u_k) + ε_k, ε_k ~ N(0, diag(σ²)/n_k), with the
/// direction u_k of each position an unknown nuisance (two angles). The
/// Fisher information of θ is formed with the nuisance eliminated (Schur
/// complement of each position's 2×2 block); the bound is its inverse.
#pragma once

#include <span>

#include <Eigen/Core>

#include "mpcal/model.h"

namespace mpcal {

struct BoundPosition {
  Eigen::Vector3d direction;  ///< unit vector of gravity reaction (sensor frame, true)
  Eigen::Vector3d noise_std_mps2;  ///< per-sample white-noise σ of each axis
  std::size_t samples = 0;
  /// The middle of the position from the drift's reference time (s); only
  /// CramerRaoBoundWithDrift uses it.
  double time_from_reference_s = 0.0;
};

/// Covariance bound of the packed parameters (order of kParameterNames); for
/// kBiasScale6 the angle rows/columns are zero and the angles are known.
/// \throws mpcal::Error if the information matrix is singular (the positions
///   do not determine the parameters).
Eigen::Matrix<double, 9, 9> CramerRaoBound(const ErrorModel& truth,
                                           std::span<const BoundPosition> positions,
                                           double gravity_mps2,
                                           ModelKind model = ModelKind::kShinElSheimy9);

/// The same bound when the bias drifts linearly in time, b(t) = b + d·(t −
/// t_ref), and the three rates d are estimated too: the bound of the packed
/// parameters (the bias at t_ref) with d eliminated.
Eigen::Matrix<double, 9, 9> CramerRaoBoundWithDrift(
    const ErrorModel& truth,
    std::span<const BoundPosition> positions,
    double gravity_mps2,
    ModelKind model = ModelKind::kShinElSheimy9);

}  // namespace mpcal
