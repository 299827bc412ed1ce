// The Cramér-Rao bound with each position's direction as a nuisance
// parameter (docs/method.md §3.8). Derivatives of the forward model come from
// ceres::Jet through the same templated ErrorModelT the users call.
#include "mpcal/cramer_rao.h"

#include <ceres/jet.h>
#include <fmt/format.h>

#include <Eigen/Cholesky>
#include <Eigen/Geometry>
#include <Eigen/LU>

#include "mpcal/error.h"

namespace mpcal {
namespace {

// Parameters + two direction angles per position.
using Jet = ceres::Jet<double, kNumModelParameters + 2>;

// Reciprocal condition below which the information matrix is singular.
constexpr double kSingularReciprocalCondition = 1e-12;

// The bound of the packed parameters; with `drift`, three drift rates of
// the bias are estimated besides them (columns p..p+2 of the information).
Eigen::Matrix<double, 9, 9> Bound(const ErrorModel& truth,
                                  std::span<const BoundPosition> positions,
                                  double gravity_mps2,
                                  ModelKind model,
                                  bool drift) {
  const int p = ParameterCount(model);
  const int n = p + (drift ? 3 : 0);
  Eigen::MatrixXd information = Eigen::MatrixXd::Zero(n, n);

  // Seed one derivative per packed parameter; the last two are the angles.
  double packed[kNumModelParameters];
  truth.ToParameters(packed);
  Jet jet_parameters[kNumModelParameters];
  for (int i = 0; i < kNumModelParameters; ++i) jet_parameters[i] = Jet(packed[i], i);
  const ErrorModelT<Jet> m = ErrorModelT<Jet>::FromParameters(jet_parameters);

  for (const BoundPosition& pos : positions) {
    if (pos.samples == 0 || !(pos.noise_std_mps2.minCoeff() > 0.0)) {
      throw Error("Cramér-Rao bound: every position needs samples and a positive noise");
    }
    // Tangent basis at the direction: the two angles move u within the sphere.
    const Eigen::Vector3d u = pos.direction.normalized();
    Eigen::Vector3d e1 = u.unitOrthogonal();
    Eigen::Vector3d e2 = u.cross(e1);
    Eigen::Matrix<Jet, 3, 1> direction;
    for (int i = 0; i < 3; ++i) {
      direction[i] = Jet(u[i]);
      direction[i].v[kNumModelParameters] = e1[i];
      direction[i].v[kNumModelParameters + 1] = e2[i];
    }
    const Eigen::Matrix<Jet, 3, 1> y = m.Forward(direction * Jet(gravity_mps2));

    Eigen::Matrix<double, 3, Eigen::Dynamic> j_theta = Eigen::MatrixXd::Zero(3, n);
    Eigen::Matrix<double, 3, 2> j_u;
    if (drift) {
      j_theta.rightCols(3) = pos.time_from_reference_s * Eigen::Matrix3d::Identity();
    }
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < p; ++c) j_theta(r, c) = y[r].v[c];
      j_u(r, 0) = y[r].v[kNumModelParameters];
      j_u(r, 1) = y[r].v[kNumModelParameters + 1];
    }
    // Weight of the mean of n samples: n Σ⁻¹.
    const Eigen::Matrix3d w =
        (static_cast<double>(pos.samples) * pos.noise_std_mps2.cwiseAbs2().cwiseInverse())
            .asDiagonal();
    const Eigen::Matrix2d uu = j_u.transpose() * w * j_u;
    const Eigen::MatrixXd tu = j_theta.transpose() * w * j_u;
    information += j_theta.transpose() * w * j_theta - tu * uu.inverse() * tu.transpose();
  }

  const Eigen::LDLT<Eigen::MatrixXd> ldlt(information);
  const Eigen::VectorXd d = ldlt.vectorD().cwiseAbs();
  if (ldlt.info() != Eigen::Success ||
      d.minCoeff() <= kSingularReciprocalCondition * d.maxCoeff()) {
    throw Error(fmt::format(
        "Cramér-Rao bound: the {} positions do not determine the {} parameters",
        positions.size(),
        p));
  }
  Eigen::Matrix<double, 9, 9> bound = Eigen::Matrix<double, 9, 9>::Zero();
  bound.topLeftCorner(p, p) =
      ldlt.solve(Eigen::MatrixXd::Identity(n, n)).topLeftCorner(p, p);
  return bound;
}

}  // namespace

Eigen::Matrix<double, 9, 9> CramerRaoBound(const ErrorModel& truth,
                                           std::span<const BoundPosition> positions,
                                           double gravity_mps2,
                                           ModelKind model) {
  return Bound(truth, positions, gravity_mps2, model, false);
}

Eigen::Matrix<double, 9, 9> CramerRaoBoundWithDrift(
    const ErrorModel& truth,
    std::span<const BoundPosition> positions,
    double gravity_mps2,
    ModelKind model) {
  return Bound(truth, positions, gravity_mps2, model, true);
}

}  // namespace mpcal
