#include "rotation.h"

#include <cmath>

#include <Eigen/Geometry>

namespace mpcal::internal {
namespace {

// Below this angle (rad) the series of sin and cos are used: their closed
// forms lose all digits to cancellation.
constexpr double kSmallAngleRad = 1e-4;

Eigen::Matrix3d Hat(const Eigen::Vector3d& v) {
  Eigen::Matrix3d k;
  k << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return k;
}

}  // namespace

Eigen::Matrix3d ExpSO3(const Eigen::Vector3d& phi) {
  const double theta2 = phi.squaredNorm();
  const Eigen::Matrix3d k = Hat(phi);
  double a;  // sin θ / θ
  double b;  // (1 − cos θ) / θ²
  if (theta2 < kSmallAngleRad * kSmallAngleRad) {
    a = 1.0 - theta2 / 6.0;
    b = 0.5 - theta2 / 24.0;
  } else {
    const double theta = std::sqrt(theta2);
    a = std::sin(theta) / theta;
    b = (1.0 - std::cos(theta)) / theta2;
  }
  return Eigen::Matrix3d::Identity() + a * k + b * k * k;
}

Eigen::Matrix3d RightJacobianSO3(const Eigen::Vector3d& phi) {
  const double theta2 = phi.squaredNorm();
  const Eigen::Matrix3d k = Hat(phi);
  double b;  // (1 − cos θ) / θ²
  double c;  // (θ − sin θ) / θ³
  if (theta2 < kSmallAngleRad * kSmallAngleRad) {
    b = 0.5 - theta2 / 24.0;
    c = 1.0 / 6.0 - theta2 / 120.0;
  } else {
    const double theta = std::sqrt(theta2);
    b = (1.0 - std::cos(theta)) / theta2;
    c = (theta - std::sin(theta)) / (theta2 * theta);
  }
  return Eigen::Matrix3d::Identity() - b * k + c * k * k;
}

namespace {

// exp([φ]×) and J_r(φ) from one sin/cos: the two share θ, and the
// evaluation of a turn needs both at every sample.
struct ExpAndJacobian {
  Eigen::Matrix3d exp;
  Eigen::Matrix3d right_jacobian;
};

ExpAndJacobian ExpWithRightJacobian(const Eigen::Vector3d& phi) {
  const double theta2 = phi.squaredNorm();
  const Eigen::Matrix3d k = Hat(phi);
  const Eigen::Matrix3d k2 = k * k;
  double a;  // sin θ / θ
  double b;  // (1 − cos θ) / θ²
  double c;  // (θ − sin θ) / θ³
  if (theta2 < kSmallAngleRad * kSmallAngleRad) {
    a = 1.0 - theta2 / 6.0;
    b = 0.5 - theta2 / 24.0;
    c = 1.0 / 6.0 - theta2 / 120.0;
  } else {
    const double theta = std::sqrt(theta2);
    const double s = std::sin(theta);
    a = s / theta;
    b = (1.0 - std::cos(theta)) / theta2;
    c = (theta - s) / (theta2 * theta);
  }
  return {Eigen::Matrix3d::Identity() + a * k + b * k2,
          Eigen::Matrix3d::Identity() - b * k + c * k2};
}

// φ of one interval (trapezoid plus the two-sample coning term).
Eigen::Vector3d StepRotationVector(const Eigen::Vector3d& mb, const Eigen::Vector3d& mc) {
  return 0.5 * (mb + mc) + mb.cross(mc) / 12.0;
}

}  // namespace

Eigen::Matrix3d RotationOverTurn(const Eigen::Matrix3d& m,
                                 std::span<const TurnStep> steps,
                                 Eigen::Matrix<double, 3, 9>* jacobian) {
  Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
  if (jacobian == nullptr) {
    for (const TurnStep& s : steps)
      r = r * ExpSO3(StepRotationVector(m * s.begin, m * s.end));
    return r;
  }
  // Σ_i R_{i+1} J_r(φ_i) δφ_i, accumulated as a 3 × 9 map of δM.
  Eigen::Matrix<double, 3, 9> sum = Eigen::Matrix<double, 3, 9>::Zero();
  for (const TurnStep& s : steps) {
    const Eigen::Vector3d mb = m * s.begin;
    const Eigen::Vector3d mc = m * s.end;
    const ExpAndJacobian e = ExpWithRightJacobian(StepRotationVector(mb, mc));
    r = r * e.exp;
    const Eigen::Matrix3d p = r * e.right_jacobian;
    const Eigen::Vector3d a = 0.5 * (s.begin + s.end);
    const Eigen::Matrix3d pb = p * Hat(mb) / 12.0;  // P [Mb]× / 12
    const Eigen::Matrix3d pc = p * Hat(mc) / 12.0;  // P [Mc]× / 12
    for (int row = 0; row < 3; ++row) {
      for (int col = 0; col < 3; ++col) {
        sum.col(3 * row + col) +=
            a[col] * p.col(row) + s.end[col] * pb.col(row) - s.begin[col] * pc.col(row);
      }
    }
  }
  *jacobian = r.transpose() * sum;
  return r;
}

Eigen::Matrix3d RotationOverTurnAlong(const Eigen::Matrix3d& m,
                                      std::span<const TurnStep> steps,
                                      const Eigen::Matrix3d& direction,
                                      Eigen::Vector3d* derivative) {
  Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const TurnStep& s : steps) {
    const Eigen::Vector3d mb = m * s.begin;
    const Eigen::Vector3d mc = m * s.end;
    const ExpAndJacobian e = ExpWithRightJacobian(StepRotationVector(mb, mc));
    r = r * e.exp;
    const Eigen::Vector3d db = direction * s.begin;
    const Eigen::Vector3d dc = direction * s.end;
    // δφ = D (b + c)/2 + (D b × M c + M b × D c)/12.
    const Eigen::Vector3d d_phi = 0.5 * (db + dc) + (db.cross(mc) + mb.cross(dc)) / 12.0;
    sum += r * (e.right_jacobian * d_phi);
  }
  *derivative = r.transpose() * sum;
  return r;
}

}  // namespace mpcal::internal
