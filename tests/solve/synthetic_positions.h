// Static-position means drawn straight from the model of docs/method.md §3.8,
// Ȳ_k = b + diag(1+s) T⁻¹ (g u_k) + ε_k, without a time series: the fast way
// to test the estimator itself, hundreds of times.
#pragma once

#include <random>
#include <vector>

#include <Eigen/Geometry>

#include "mpcal/cramer_rao.h"
#include "mpcal/model.h"
#include "mpcal/solve.h"

namespace mpcal::testing {

inline constexpr double kTestGravityMps2 = 9.80665;

/// The 26 directions of Syed et al.: faces, edges, corners of a cube.
inline std::vector<Eigen::Vector3d> CubeDirections() {
  std::vector<Eigen::Vector3d> d;
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z)
        if (x != 0 || y != 0 || z != 0)
          d.push_back(Eigen::Vector3d(x, y, z).normalized());
  return d;
}

/// Each direction tilted by a random rotation of up to `tilt_rad`.
inline std::vector<Eigen::Vector3d> Tilted(std::vector<Eigen::Vector3d> d,
                                           double tilt_rad,
                                           std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (auto& v : d) {
    const Eigen::Vector3d axis = Eigen::Vector3d(u(rng), u(rng), u(rng)).normalized();
    v = Eigen::AngleAxisd(tilt_rad * u(rng), axis) * v;
  }
  return d;
}

struct SyntheticSession {
  std::vector<PositionObservation> positions;
  std::vector<BoundPosition> bound_positions;
};

/// Means of `samples` samples with white noise `noise_mps2` per axis.
inline SyntheticSession MakeSession(const ErrorModel& truth,
                                    const std::vector<Eigen::Vector3d>& directions,
                                    const Eigen::Vector3d& noise_mps2,
                                    std::size_t samples,
                                    std::mt19937_64& rng) {
  std::normal_distribution<double> n(0.0, 1.0);
  SyntheticSession s;
  for (const auto& u : directions) {
    PositionObservation p;
    const double sd = 1.0 / std::sqrt(static_cast<double>(samples));
    p.mean_mps2 = truth.Forward(kTestGravityMps2 * u) +
                  Eigen::Vector3d(n(rng), n(rng), n(rng)).cwiseProduct(noise_mps2) * sd;
    // The sample std of n samples scatters by 1/sqrt(2n) around σ.
    const double spread = 1.0 / std::sqrt(2.0 * static_cast<double>(samples));
    p.sample_std_mps2 = noise_mps2.cwiseProduct(
        Eigen::Vector3d::Ones() + spread * Eigen::Vector3d(n(rng), n(rng), n(rng)));
    p.samples = samples;
    s.positions.push_back(p);
    s.bound_positions.push_back({u, noise_mps2, samples});
  }
  return s;
}

/// Errors of a consumer-grade part (bias 0.3 g, scale 6 %,
/// non-orthogonality 0.02 rad).
inline ErrorModel ConsumerGrade() {
  ErrorModel m;
  m.bias_mps2 = Eigen::Vector3d(0.3, -0.25, 0.2) * kTestGravityMps2;
  m.scale_factor_error = {0.06, -0.05, 0.04};
  m.theta_yz_rad = 0.02;
  m.theta_zx_rad = -0.015;
  m.theta_zy_rad = 0.01;
  return m;
}

}  // namespace mpcal::testing
