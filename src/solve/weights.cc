#include "weights.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace mpcal::internal {

std::vector<Eigen::Vector3d> UsableNoise(std::span<const PositionObservation> positions) {
  // The median over positions is the typical noise of each axis; a position
  // far below it is quantisation, not a better sensor.
  Eigen::Vector3d typical = Eigen::Vector3d::Zero();
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<double> s;
    s.reserve(positions.size());
    for (const auto& p : positions) s.push_back(p.sample_std_mps2[axis]);
    std::nth_element(s.begin(), s.begin() + s.size() / 2, s.end());
    typical[axis] = s.empty() ? 0.0 : s[s.size() / 2];
  }
  // With no noise at all (synthetic means), any common level gives the same
  // estimate; the a-posteriori variance factor carries the scale.
  const double floor_mps2 = std::max(1e-3 * typical.maxCoeff(), 1e-9);
  std::vector<Eigen::Vector3d> noise;
  noise.reserve(positions.size());
  for (const auto& p : positions) {
    Eigen::Vector3d n;
    for (int axis = 0; axis < 3; ++axis) {
      n[axis] = std::max({p.sample_std_mps2[axis], 0.5 * typical[axis], floor_mps2});
    }
    noise.push_back(n);
  }
  return noise;
}

double ResidualSigma(const ErrorModel& model, const Eigen::Vector3d& mean_mps2,
                     const Eigen::Vector3d& noise_mps2, std::size_t samples) {
  // ∇_Y |a| = (a/|a|)ᵀ T diag(1/(1+s)).
  const Eigen::Vector3d a = model.Correct(mean_mps2);
  const Eigen::RowVector3d gradient =
      (a.normalized().transpose() * model.NonOrthogonality())
          .cwiseQuotient((Eigen::Vector3d::Ones() + model.scale_factor_error).transpose());
  const double variance =
      gradient.cwiseProduct(noise_mps2.transpose()).squaredNorm() /
      static_cast<double>(std::max<std::size_t>(samples, 1));
  return std::sqrt(variance);
}

}  // namespace mpcal::internal
