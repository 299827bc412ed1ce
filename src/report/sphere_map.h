// The map of the sphere of orientations: where gravity pointed in the sensor
// frame at each static position, on two hemispheres (z ≥ 0 and z < 0) in the
// azimuthal equal-area projection, with the 26 canonical cube directions of
// Syed et al. (2007) marked covered or missing.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace mpcal::report {

/// One static position: the direction of its mean reading (any length).
struct SpherePoint {
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
  std::string label;  ///< e.g. the position number
  bool used = true;   ///< false: excluded from the fit
};

/// A direction of the 26 (faces, edges, corners of a cube).
struct CanonicalDirection {
  Eigen::Vector3d direction;  ///< unit vector
  std::string name;           ///< what points down, e.g. "-x+y edge"
  bool covered = false;
};

/// Angular distance under which a position covers a canonical direction:
/// just under half the 45° between a face and its neighbouring edge, so no
/// position covers two directions at once.
inline constexpr double kCoverageToleranceDeg = 22.0;

/// The 26 canonical directions, faces first, then edges, then corners, each
/// covered when a used point lies within `tolerance_deg` of it.
std::vector<CanonicalDirection> CanonicalCoverage(
    const std::vector<SpherePoint>& points, double tolerance_deg = kCoverageToleranceDeg);

struct SphereMapSpec {
  std::string aria_label;
  std::vector<SpherePoint> points;
  std::vector<CanonicalDirection> canonical;
  double width = 760.0;
};

/// The <svg> of the map: two disks, both seen from +z with x to the right
/// and y up, so that the same azimuth is at the same place on each.
std::string SphereMap(const SphereMapSpec& spec);

}  // namespace mpcal::report
