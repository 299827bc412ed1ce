#include "sphere_fit.h"

#include <cmath>

#include <Eigen/QR>

namespace mpcal::internal {
namespace {

// Reciprocal condition of the sphere-fit design below which the points are
// too close to a plane for the centre to be trusted: points whose spread
// across the plane is at the noise level (1e-4 of g) would otherwise put the
// centre hundreds of g away. Positions within 27° of one axis still give 0.1.
constexpr double kMinReciprocalCondition = 1e-2;

}  // namespace

Sphere FitSphere(std::span<const Eigen::Vector3d> points) {
  Sphere result;
  if (points.empty()) return result;
  Eigen::Vector3d lo = points.front(), hi = lo;
  for (const auto& y : points) {
    lo = lo.cwiseMin(y);
    hi = hi.cwiseMax(y);
  }
  // Centre the design on the mid-range: raw counts near 32768 would otherwise
  // square to numbers that swamp the small differences the fit needs.
  const Eigen::Vector3d mid = 0.5 * (lo + hi);
  const Eigen::Index n = static_cast<Eigen::Index>(points.size());
  Eigen::MatrixXd design(n, 4);
  Eigen::VectorXd rhs(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Vector3d y = points[static_cast<std::size_t>(k)] - mid;
    design.row(k) << 2.0 * y.transpose(), 1.0;
    rhs[k] = y.squaredNorm();
  }
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(design);
  const Eigen::VectorXd diag = qr.matrixQR().diagonal().cwiseAbs();
  if (n >= 4 && diag.minCoeff() > kMinReciprocalCondition * diag.maxCoeff()) {
    const Eigen::Vector4d x = qr.solve(rhs);
    const double r2 = x[3] + x.head<3>().squaredNorm();
    if (r2 > 0.0) {
      result.centre = mid + x.head<3>();
      result.radius = std::sqrt(r2);
      return result;
    }
  }
  result.centre = mid;
  result.radius = 0.5 * (hi - lo).maxCoeff();
  return result;
}

}  // namespace mpcal::internal
