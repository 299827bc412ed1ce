// The sphere the static means lie on: the offset and one g of the readings.
#include "mpcal/sphere_fit.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include <Eigen/Dense>

namespace mpcal {
namespace {

// Fallback offset (see the header): 0, or for unsigned ADC counts the power of
// two nearest the median reading.
Eigen::Vector3d FallbackCentre(std::span<const Eigen::Vector3d> means, AccelUnits units) {
  if (units != AccelUnits::kCounts || means.empty()) return Eigen::Vector3d::Zero();
  std::vector<double> c;
  for (const auto& m : means) {
    for (int i = 0; i < 3; ++i) {
      if (m[i] < 0.0) return Eigen::Vector3d::Zero();
      c.push_back(m[i]);
    }
  }
  std::nth_element(
      c.begin(), c.begin() + static_cast<std::ptrdiff_t>(c.size() / 2), c.end());
  const double median = c[c.size() / 2];
  if (median < 1.0) return Eigen::Vector3d::Zero();
  const double p = std::exp2(std::round(std::log2(median)));
  return std::abs(median - p) < 0.5 * p ? Eigen::Vector3d::Constant(p)
                                        : Eigen::Vector3d::Zero();
}

}  // namespace

SphereFit FitSphere(std::span<const Eigen::Vector3d> means, AccelUnits units) {
  SphereFit fit;
  if (means.empty()) return fit;
  // Linear least squares |m|² = 2 m·c + d on means centred on their average
  // (counts near 32768 square to 1e9 and would swamp the noise otherwise),
  // scaled to unit RMS so that the conditioning test below is unit-free.
  Eigen::Vector3d avg = Eigen::Vector3d::Zero();
  for (const auto& m : means) avg += m;
  avg /= static_cast<double>(means.size());
  double spread = 0.0;
  for (const auto& m : means) spread += (m - avg).squaredNorm();
  spread = std::sqrt(spread / static_cast<double>(means.size()));

  bool fitted = false;
  Eigen::Vector3d centre = FallbackCentre(means, units);
  if (means.size() >= 4 && spread > 0.0) {
    const auto k = static_cast<Eigen::Index>(means.size());
    Eigen::MatrixXd design(k, 4);
    Eigen::VectorXd rhs(k);
    for (Eigen::Index i = 0; i < k; ++i) {
      const Eigen::Vector3d q = (means[static_cast<std::size_t>(i)] - avg) / spread;
      design.row(i) << 2 * q.x(), 2 * q.y(), 2 * q.z(), 1.0;
      rhs(i) = q.squaredNorm();
    }
    const Eigen::JacobiSVD<Eigen::MatrixXd> svd(design);
    const Eigen::VectorXd& s = svd.singularValues();
    if (s(3) > 1e-3 * s(0)) {
      const Eigen::Vector4d x = design.colPivHouseholderQr().solve(rhs);
      const Eigen::Vector3d c = avg + spread * x.head<3>();
      // A fit through positions that all sit on a small cap can put the
      // centre anywhere along the cap's axis: accept it only when the
      // directions about it spread out (their mean is short).
      Eigen::Vector3d mean_dir = Eigen::Vector3d::Zero();
      bool finite = c.allFinite();
      for (const auto& m : means) {
        const Eigen::Vector3d d = m - c;
        if (!(d.norm() > 0.0)) finite = false;
        mean_dir += d.normalized();
      }
      mean_dir /= static_cast<double>(means.size());
      // And only when the positions spread over a good part of the sphere
      // (their RMS distance from their average is r for the whole sphere,
      // 0.3 r for a cap of 17°), with a radius near 1 g when the unit says
      // what 1 g is.
      const double radius = (means.front() - c).norm();
      bool plausible = radius < 2.5 * spread;
      if (const auto per_unit = FixedMps2PerUnit(units)) {
        const double g_units = kStandardGravityMps2 / *per_unit;
        plausible = plausible && radius > 0.7 * g_units && radius < 1.3 * g_units;
      }
      if (finite && plausible && mean_dir.norm() < 0.8) {
        centre = c;
        fitted = true;
      }
    }
  }
  fit.centre = centre;
  fit.fitted = fitted;
  std::vector<double> r;
  for (const auto& m : means) r.push_back((m - centre).norm());
  double sum = 0.0;
  for (double v : r) sum += v;
  fit.radius = sum / static_cast<double>(r.size());
  double ss = 0.0;
  for (double v : r) ss += (v - fit.radius) * (v - fit.radius);
  fit.residual_rms = std::sqrt(ss / static_cast<double>(r.size()));
  return fit;
}

}  // namespace mpcal
