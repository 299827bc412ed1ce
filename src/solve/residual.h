// The residual of one static position, eq 11 of Souza & Machado (2016) in the
// |a| − g form of docs/method.md §3.4 (same minimiser, better scaling),
// whitened by its standard deviation so that every position counts by its
// precision.
#pragma once

#include <Eigen/Core>

#include "mpcal/model.h"

namespace mpcal::internal {

struct MagnitudeResidual {
  MagnitudeResidual(const Eigen::Vector3d& mean_mps2,
                    double gravity_mps2,
                    double sigma_mps2)
      : mean_mps2_(mean_mps2), gravity_mps2_(gravity_mps2), sigma_mps2_(sigma_mps2) {}

  /// Parameter blocks as the problem holds them: bias (3), scale-factor
  /// error (3), non-orthogonality angles θyz, θzx, θzy (3).
  template <typename T>
  bool operator()(const T* bias, const T* scale, const T* angles, T* residual) const {
    ErrorModelT<T> m;
    m.bias_mps2 = Eigen::Map<const Eigen::Matrix<T, 3, 1>>(bias);
    m.scale_factor_error = Eigen::Map<const Eigen::Matrix<T, 3, 1>>(scale);
    m.theta_yz_rad = angles[0];
    m.theta_zx_rad = angles[1];
    m.theta_zy_rad = angles[2];
    const Eigen::Matrix<T, 3, 1> a = m.Correct(mean_mps2_.cast<T>());
    residual[0] = (a.norm() - T(gravity_mps2_)) / T(sigma_mps2_);
    return true;
  }

 private:
  Eigen::Vector3d mean_mps2_;
  double gravity_mps2_;
  double sigma_mps2_;
};

/// The same with a bias that drifts linearly in time (README, "Time-varying
/// bias"): b(t) = b + d·(t − t_ref), the position held `dt_s` = t − t_ref
/// from the reference time (its middle).
struct DriftMagnitudeResidual {
  DriftMagnitudeResidual(const Eigen::Vector3d& mean_mps2,
                         double gravity_mps2,
                         double sigma_mps2,
                         double dt_s)
      : base_(mean_mps2, gravity_mps2, sigma_mps2), dt_s_(dt_s) {}

  template <typename T>
  bool operator()(
      const T* bias, const T* scale, const T* angles, const T* drift, T* residual) const {
    T at_position[3];
    for (int i = 0; i < 3; ++i) at_position[i] = bias[i] + drift[i] * T(dt_s_);
    return base_(at_position, scale, angles, residual);
  }

 private:
  MagnitudeResidual base_;
  double dt_s_;
};

}  // namespace mpcal::internal
