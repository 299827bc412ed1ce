// The exponential map of SO(3) and the cached evaluation of a turn: the
// series used at small angles against the closed forms, and a cached
// residual or Jacobian identical to a fresh one.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "gyro/rotation.h"
#include "gyro/turn_problem.h"

namespace mpcal {
namespace {

// A double's rounding over a few operations on entries of order 1.
constexpr double kRoundingTol = 4e-16;

Eigen::Matrix3d Hat(const Eigen::Vector3d& v) {
  Eigen::Matrix3d k;
  k << 0.0, -v.z(), v.y(), v.z(), 0.0, -v.x(), -v.y(), v.x(), 0.0;
  return k;
}

// J_r(φ) in closed form, evaluated in long double so that its cancellation
// at small angles stays below the tolerance of a double.
Eigen::Matrix3d RightJacobianReference(const Eigen::Vector3d& phi) {
  const long double t = phi.norm();
  const long double b = (1.0L - std::cos(t)) / (t * t);
  const long double c = (t - std::sin(t)) / (t * t * t);
  const Eigen::Matrix3d k = Hat(phi);
  return Eigen::Matrix3d::Identity() - static_cast<double>(b) * k +
         static_cast<double>(c) * k * k;
}

TEST(ExpSO3, MatchesTheAngleAxisRotationOnBothSidesOfTheSeries) {
  // Per-sample angles of a turn (1e-6-0.05 rad), the series' limit (0.25
  // rad) on both sides, and large angles.
  for (double angle : {1e-6, 1e-3, 0.05, 0.2499999, 0.25, 0.2500001, 1.0, 3.0}) {
    const Eigen::Vector3d axis = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
    const Eigen::Matrix3d expected = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
    const Eigen::Matrix3d r = internal::ExpSO3(angle * axis);
    EXPECT_LT((r - expected).cwiseAbs().maxCoeff(), kRoundingTol) << angle;
    EXPECT_LT((r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(),
              kRoundingTol)
        << angle;
  }
}

TEST(RightJacobianSO3, MatchesTheClosedFormInExtendedPrecision) {
  for (double angle : {1e-3, 0.05, 0.2499999, 0.2500001, 1.0}) {
    const Eigen::Vector3d phi = angle * Eigen::Vector3d(-0.2, 0.9, 0.4).normalized();
    EXPECT_LT((internal::RightJacobianSO3(phi) - RightJacobianReference(phi))
                  .cwiseAbs()
                  .maxCoeff(),
              kRoundingTol)
        << angle;
  }
}

internal::TurnData SomeTurn() {
  internal::TurnData t;
  for (int i = 0; i < 150; ++i) {
    const double s = 0.04 * i;
    t.steps.push_back(
        {Eigen::Vector3d(0.02 * std::sin(s), 0.015 * std::cos(s), 0.01),
         Eigen::Vector3d(0.02 * std::sin(s + 0.04), 0.015 * std::cos(s + 0.04), 0.008)});
  }
  t.u_from = Eigen::Vector3d(0.1, 0.2, 0.97).normalized();
  t.u_to = Eigen::Vector3d(0.6, -0.1, 0.79).normalized();
  const Eigen::Vector3d e1 = t.u_to.unitOrthogonal();
  t.basis_to.col(0) = e1;
  t.basis_to.col(1) = t.u_to.cross(e1);
  return t;
}

TEST(TurnResidual, CachedValuesEqualAFreshEvaluation) {
  const internal::TurnData turn = SomeTurn();
  Eigen::Matrix3d m0;
  m0 << 1.03, 0.01, -0.02, 0.015, 0.97, 0.03, -0.01, 0.02, 1.01;
  const Eigen::Matrix3d m1 = m0 + 1e-3 * Eigen::Matrix3d::Ones();
  const Eigen::Matrix3d m2 = m0 - 2e-3 * Eigen::Matrix3d::Identity();
  // As the solver calls it: residual only at a candidate, then the
  // Jacobian at the same point, with a rejected candidate in between.
  Eigen::Vector2d r0;
  internal::TurnResidual(turn, m0, &r0, nullptr);
  internal::TurnResidual(turn, m1, nullptr, nullptr);
  internal::TurnResidual(turn, m2, nullptr, nullptr);
  for (const Eigen::Matrix3d& m : {m0, m1, m2}) {
    Eigen::Vector2d cached_r;
    Eigen::Matrix<double, 2, 9> cached_j;
    const Eigen::Matrix3d cached = internal::TurnResidual(turn, m, &cached_r, &cached_j);
    const internal::TurnData fresh_turn = SomeTurn();
    Eigen::Vector2d fresh_r;
    Eigen::Matrix<double, 2, 9> fresh_j;
    const Eigen::Matrix3d fresh =
        internal::TurnResidual(fresh_turn, m, &fresh_r, &fresh_j);
    EXPECT_EQ(cached, fresh);
    EXPECT_EQ(cached_r, fresh_r);
    EXPECT_EQ(cached_j, fresh_j);
  }
  Eigen::Vector2d again;
  internal::TurnResidual(turn, m0, &again, nullptr);
  EXPECT_EQ(again, r0);
}

TEST(TurnResidualAlong, DerivativeIsTheJacobianAlongTheDirection) {
  const internal::TurnData turn = SomeTurn();
  Eigen::Matrix3d m;
  m << 0.98, -0.02, 0.01, 0.03, 1.02, -0.01, 0.02, 0.0, 0.99;
  Eigen::Matrix3d direction;
  direction << 1.0, 0.2, -0.1, 0.0, 0.7, 0.3, -0.4, 0.1, 1.2;
  Eigen::Vector2d r;
  Eigen::Matrix<double, 2, 9> j;
  internal::TurnResidual(turn, m, &r, &j);
  Eigen::Vector2d r_along;
  Eigen::Vector2d d_along;
  internal::TurnResidualAlong(turn, m, direction, &r_along, &d_along);
  const Eigen::Matrix<double, 9, 1> d_m = Eigen::Map<const Eigen::Matrix<double, 9, 1>>(
      Eigen::Matrix<double, 3, 3, Eigen::RowMajor>(direction).data());
  EXPECT_LT((r_along - r).norm(), 1e-15);
  EXPECT_LT((d_along - j * d_m).norm(), 1e-12 * (j * d_m).norm());
}

}  // namespace
}  // namespace mpcal
