// Six-position initialisation (Syed et al. 2007, docs/method.md §3.3): without it
// the multi-position least squares can fail to converge for low-cost parts.
#include <cmath>
#include <limits>
#include <vector>

#include <fmt/format.h>

#include "mpcal/coverage.h"
#include "mpcal/error.h"
#include "mpcal/solve.h"

namespace mpcal {
namespace {

// cos 60°: the least share of gravity along an axis for its up and down
// positions to tell its scale.
constexpr double kMinAxisComponent = 0.5;

}  // namespace

ErrorModel InitialiseSixPosition(std::span<const PositionObservation> positions,
                                 double gravity_mps2) {
  if (positions.size() < 2) {
    throw Error(fmt::format(
        "six-position initialisation needs at least 2 static positions, got {}",
        positions.size()));
  }
  // Directions are judged from the centre of the sphere the means lie on, so
  // that a large bias (0.5 g parts) does not decide which axis points up,
  // even when the positions crowd one hemisphere.
  std::vector<Eigen::Vector3d> means;
  for (const auto& p : positions) means.push_back(p.mean_mps2);
  const Eigen::Vector3d centre = FitSphere(means, AccelUnits::kMps2).centre;

  ErrorModel m;
  for (int axis = 0; axis < 3; ++axis) {
    double best_up = -std::numeric_limits<double>::infinity();
    double best_down = std::numeric_limits<double>::infinity();
    Eigen::Vector3d up = Eigen::Vector3d::Zero(), down = Eigen::Vector3d::Zero();
    for (const auto& p : positions) {
      const Eigen::Vector3d d = p.mean_mps2 - centre;
      const double norm = d.norm();
      if (norm <= 0.0) continue;
      const double c = d[axis] / norm;
      if (c > best_up) best_up = c, up = p.mean_mps2;
      if (c < best_down) best_down = c, down = p.mean_mps2;
    }
    // An axis that never came near vertical (within 60°) says nothing about
    // its scale; start it ideal and let the observability check speak.
    if (best_up < kMinAxisComponent || best_down > -kMinAxisComponent) {
      m.bias_mps2[axis] = centre[axis];
      continue;
    }
    m.bias_mps2[axis] = 0.5 * (up[axis] + down[axis]);
    m.scale_factor_error[axis] = 0.5 * (up[axis] - down[axis]) / gravity_mps2 - 1.0;
  }
  return m;
}

}  // namespace mpcal
