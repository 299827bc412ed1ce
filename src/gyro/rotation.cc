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

Eigen::Matrix3d RotationOverTurn(const Eigen::Matrix3d& m,
                                 std::span<const TurnStep> steps,
                                 Eigen::Matrix<double, 3, 9>* jacobian) {
  Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
  // Σ_i R_{i+1} J_r(φ_i) δφ_i, accumulated as a 3 × 9 map of δM.
  Eigen::Matrix<double, 3, 9> sum = Eigen::Matrix<double, 3, 9>::Zero();
  for (const TurnStep& s : steps) {
    const Eigen::Vector3d mb = m * s.begin;
    const Eigen::Vector3d mc = m * s.end;
    const Eigen::Vector3d phi = 0.5 * (mb + mc) + mb.cross(mc) / 12.0;
    r = r * ExpSO3(phi);
    if (jacobian == nullptr) continue;
    const Eigen::Matrix3d p = r * RightJacobianSO3(phi);
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
  if (jacobian != nullptr) *jacobian = r.transpose() * sum;
  return r;
}

}  // namespace mpcal::internal
