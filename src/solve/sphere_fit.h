// The sphere the static-position means lie near: centre ≈ bias, radius ≈ g
// in the readings' units. It finds the offset and nominal scale of raw ADC
// counts from the positions themselves (imu_tk makes its users type them
// into code), and the centre from which each position's direction is judged
// in the six-position initialisation.
#pragma once

#include <span>

#include <Eigen/Core>

namespace mpcal::internal {

struct Sphere {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double radius = 0.0;
};

/// Least-squares sphere through `points`: |Y|² = 2cᵀY + (R² − |c|²) is
/// linear in c and R² − |c|². Falls back to the per-axis mid-range and the
/// largest half-span when the points do not span three dimensions.
Sphere FitSphere(std::span<const Eigen::Vector3d> points);

}  // namespace mpcal::internal
