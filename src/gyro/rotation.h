// Rotation over a turn by the exponential map: R = Π exp([φ_i]×), with φ_i
// the rotation vector of sample interval i from the bias-free readings at
// its two ends (raw units, times the interval: b_i, c_i) through the 3×3
// gyroscope matrix M, for a rate linear over the interval (Bortz 1971):
//   φ_i = M (b_i + c_i)/2 + (M b_i × M c_i)/12,
// the trapezoid plus the two-sample coning term (without it, the hand's
// fast wobble during a turn leaves 0.1° at 100 Hz). Two forms of the same product: one
// templated on the scalar (ceres::Jet goes through it, the reference for the
// derivatives), and one in doubles with the analytic Jacobian with respect
// to M, the one the solver uses (a 9-wide Jet through 20 000 exponentials
// per evaluation is ten times slower).
#pragma once

#include <span>

#include <ceres/rotation.h>

#include <Eigen/Core>

namespace mpcal::internal {

/// One sample interval: the bias-free readings at its start and end, each
/// times the interval's length (raw units × s).
struct TurnStep {
  Eigen::Vector3d begin = Eigen::Vector3d::Zero();
  Eigen::Vector3d end = Eigen::Vector3d::Zero();
};

/// R_begin_end from `increments` with M given row-major in `m` (9 values):
/// maps vectors in the body frame at the end to the frame at the start.
/// Quaternion products of ceres' AngleAxisToQuaternion, which keeps its
/// derivatives exact at small angles.
template <typename T>
Eigen::Matrix<T, 3, 3> RotationOverTurn(const T* m, std::span<const TurnStep> steps) {
  T q[4] = {T(1), T(0), T(0), T(0)};
  for (const TurnStep& step_in : steps) {
    T b[3];
    T c[3];
    for (int r = 0; r < 3; ++r) {
      b[r] = m[3 * r] * step_in.begin[0] + m[3 * r + 1] * step_in.begin[1] +
             m[3 * r + 2] * step_in.begin[2];
      c[r] = m[3 * r] * step_in.end[0] + m[3 * r + 1] * step_in.end[1] +
             m[3 * r + 2] * step_in.end[2];
    }
    T phi[3];
    phi[0] = T(0.5) * (b[0] + c[0]) + (b[1] * c[2] - b[2] * c[1]) / T(12);
    phi[1] = T(0.5) * (b[1] + c[1]) + (b[2] * c[0] - b[0] * c[2]) / T(12);
    phi[2] = T(0.5) * (b[2] + c[2]) + (b[0] * c[1] - b[1] * c[0]) / T(12);
    T step[4];
    ceres::AngleAxisToQuaternion(phi, step);
    T next[4];
    ceres::QuaternionProduct(q, step, next);
    for (int i = 0; i < 4; ++i) q[i] = next[i];
  }
  Eigen::Matrix<T, 3, 3, Eigen::RowMajor> r;
  ceres::QuaternionToRotation(q, r.data());
  return r;
}

/// The same rotation in doubles and, when `jacobian` is not null, the right
/// perturbation δθ of R (R' = R exp([δθ]×)) per change of M (3 × 9,
/// row-major entries of M):
///   δθ = Rᵀ Σ_i R_{i+1} J_r(φ_i) δφ_i,  R_{i+1} = Π_{j≤i} exp(φ_j),
///   δφ_i = δM a_i − [M c_i]× δM b_i / 12 + [M b_i]× δM c_i / 12.
Eigen::Matrix3d RotationOverTurn(const Eigen::Matrix3d& m,
                                 std::span<const TurnStep> steps,
                                 Eigen::Matrix<double, 3, 9>* jacobian);

/// The same rotation and the derivative of its right perturbation δθ along
/// one direction of M (δM = `direction`): 3 values per sample where the
/// full Jacobian needs 27, for a fit of fewer parameters (a common scale).
Eigen::Matrix3d RotationOverTurnAlong(const Eigen::Matrix3d& m,
                                      std::span<const TurnStep> steps,
                                      const Eigen::Matrix3d& direction,
                                      Eigen::Vector3d* derivative);

/// exp([φ]×) (Rodrigues), and the right Jacobian of SO(3) at φ.
Eigen::Matrix3d ExpSO3(const Eigen::Vector3d& phi);
Eigen::Matrix3d RightJacobianSO3(const Eigen::Vector3d& phi);

}  // namespace mpcal::internal
