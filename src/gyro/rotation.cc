#include "rotation.h"

#include <array>
#include <cmath>
#include <cstddef>

#include <Eigen/Geometry>

namespace mpcal::internal {
namespace {

// Below this angle (rad) the coefficients of the exponential and its
// Jacobian come from their series in θ² to the θ¹⁰ term: the first term left
// out is under 1e-17 of each (θ¹²/13! at 0.25 rad), below a double's
// rounding, and the series needs no square root, sine or cosine; the closed
// forms lose digits to cancellation at small angles ((θ − sin θ)/θ³: two at
// 0.25 rad, five at 0.01 rad). A turn's per-sample angles at 100 Hz are
// 0.001-0.05 rad.
constexpr double kSeriesAngleRad = 0.25;

// The helpers of the per-sample loops are forced inline (gnu::always_inline):
// GCC keeps them as calls returning 3 × 3 matrices through memory, which cost
// a third of a turn's evaluation (bench/gyro_speed_bench.cc).

// Σ_{k=0..5} (−x)^k/(2k + kFirst)!, by Horner's rule on coefficients
// computed at compile time.
template <int kFirst>
constexpr std::array<double, 6> SeriesCoefficients() {
  std::array<double, 6> c{};
  for (std::size_t k = 0; k < c.size(); ++k) {
    double factorial = 1.0;
    for (std::size_t n = 2; n <= 2 * k + kFirst; ++n) factorial *= static_cast<double>(n);
    c[k] = 1.0 / factorial;
  }
  return c;
}

template <int kFirst>
[[gnu::always_inline]] inline double AlternatingSeries(double x) {
  static constexpr std::array<double, 6> kCoefficients = SeriesCoefficients<kFirst>();
  double sum = 0.0;
  for (auto c = kCoefficients.rbegin(); c != kCoefficients.rend(); ++c)
    sum = *c - x * sum;
  return sum;
}

// sin θ/θ, (1 − cos θ)/θ² and (θ − sin θ)/θ³ at θ² = `theta2`.
struct SO3Coefficients {
  double a;
  double b;
  double c;
};

[[gnu::always_inline]] inline SO3Coefficients CoefficientsAt(double theta2) {
  if (theta2 < kSeriesAngleRad * kSeriesAngleRad) {
    return {AlternatingSeries<1>(theta2),
            AlternatingSeries<2>(theta2),
            AlternatingSeries<3>(theta2)};
  }
  const double theta = std::sqrt(theta2);
  const double s = std::sin(theta);
  return {s / theta, (1.0 - std::cos(theta)) / theta2, (theta - s) / (theta2 * theta)};
}

[[gnu::always_inline]] inline Eigen::Matrix3d Hat(const Eigen::Vector3d& v) {
  Eigen::Matrix3d k;
  k << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return k;
}

// I + a [φ]× + b [φ]×², with [φ]×² = φφᵀ − θ² I.
[[gnu::always_inline]] inline Eigen::Matrix3d Exp(const Eigen::Vector3d& phi,
                                                  double theta2,
                                                  const SO3Coefficients& k) {
  Eigen::Matrix3d hat2 = phi * phi.transpose();
  hat2.diagonal().array() -= theta2;
  return Eigen::Matrix3d::Identity() + k.a * Hat(phi) + k.b * hat2;
}

}  // namespace

Eigen::Matrix3d ExpSO3(const Eigen::Vector3d& phi) {
  const double theta2 = phi.squaredNorm();
  return Exp(phi, theta2, CoefficientsAt(theta2));
}

Eigen::Matrix3d RightJacobianSO3(const Eigen::Vector3d& phi) {
  const SO3Coefficients k = CoefficientsAt(phi.squaredNorm());
  const Eigen::Matrix3d hat = Hat(phi);
  return Eigen::Matrix3d::Identity() - k.b * hat + k.c * hat * hat;
}

namespace {

// exp([φ]×) and the left Jacobian J_l(φ) = exp([φ]×) J_r(φ) from one set of
// coefficients ([φ]×² = φφᵀ − θ² I): R_{i+1} J_r(φ_i) = R_i J_l(φ_i), so a
// sample's two products with R_i do not wait for each other.
struct ExpAndJacobian {
  Eigen::Matrix3d exp;
  Eigen::Matrix3d left_jacobian;
};

[[gnu::always_inline]] inline ExpAndJacobian ExpWithLeftJacobian(
    const Eigen::Vector3d& phi) {
  const double theta2 = phi.squaredNorm();
  const SO3Coefficients k = CoefficientsAt(theta2);
  const Eigen::Matrix3d hat = Hat(phi);
  Eigen::Matrix3d hat2 = phi * phi.transpose();
  hat2.diagonal().array() -= theta2;
  return {Eigen::Matrix3d::Identity() + k.a * hat + k.b * hat2,
          Eigen::Matrix3d::Identity() + k.b * hat + k.c * hat2};
}

// φ of one interval (trapezoid plus the two-sample coning term).
[[gnu::always_inline]] inline Eigen::Vector3d StepRotationVector(
    const Eigen::Vector3d& mb, const Eigen::Vector3d& mc) {
  return 0.5 * (mb + mc) + mb.cross(mc) / 12.0;
}

}  // namespace

Eigen::Matrix3d RotationOverTurn(const Eigen::Matrix3d& m,
                                 std::span<const TurnStep> steps,
                                 Eigen::Matrix<double, 3, 9>* jacobian) {
  Eigen::Matrix3d r = Eigen::Matrix3d::Identity();
  if (jacobian == nullptr) {
    for (const TurnStep& s : steps) {
      const Eigen::Vector3d phi = StepRotationVector(m * s.begin, m * s.end);
      const double theta2 = phi.squaredNorm();
      r = r * Exp(phi, theta2, CoefficientsAt(theta2));
    }
    return r;
  }
  // Σ_i R_i J_l(φ_i) δφ_i, accumulated as a 3 × 9 map of δM.
  Eigen::Matrix<double, 3, 9> sum = Eigen::Matrix<double, 3, 9>::Zero();
  for (const TurnStep& s : steps) {
    const Eigen::Vector3d mb = m * s.begin;
    const Eigen::Vector3d mc = m * s.end;
    const ExpAndJacobian e = ExpWithLeftJacobian(StepRotationVector(mb, mc));
    const Eigen::Matrix3d p = r * e.left_jacobian;
    r = r * e.exp;
    const Eigen::Vector3d a = 0.5 * (s.begin + s.end);
    const Eigen::Matrix3d pb = p * Hat(mb / 12.0);  // P [Mb]× / 12
    const Eigen::Matrix3d pc = p * Hat(mc / 12.0);  // P [Mc]× / 12
    for (int row = 0; row < 3; ++row) {             // the columns of δM's row `row`
      sum.middleCols<3>(3 * row).noalias() += p.col(row) * a.transpose() +
                                              pb.col(row) * s.end.transpose() -
                                              pc.col(row) * s.begin.transpose();
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
    const Eigen::Vector3d phi = StepRotationVector(mb, mc);
    const double theta2 = phi.squaredNorm();
    const SO3Coefficients k = CoefficientsAt(theta2);
    const Eigen::Vector3d db = direction * s.begin;
    const Eigen::Vector3d dc = direction * s.end;
    // δφ = D (b + c)/2 + (D b × M c + M b × D c)/12, and J_l δφ = δφ +
    // b φ × δφ + c φ × (φ × δφ): three values where J_l needs nine.
    const Eigen::Vector3d d_phi = 0.5 * (db + dc) + (db.cross(mc) + mb.cross(dc)) / 12.0;
    const Eigen::Vector3d phi_d = phi.cross(d_phi);
    sum += r * (d_phi + k.b * phi_d + k.c * phi.cross(phi_d));
    r = r * Exp(phi, theta2, k);
  }
  *derivative = r.transpose() * sum;
  return r;
}

}  // namespace mpcal::internal
