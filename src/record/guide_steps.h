// The steps of the session guide that carry its rules (SessionGuide in
// guide.cc runs them): the noise pooled over the positions, the targets,
// the bound's worst parameter, the next direction, and the turns.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <vector>

#include <Eigen/Core>

#include "mpcal/record_guide.h"

namespace mpcal::internal {

/// The angle between two vectors (deg).
double AngleDeg(const Eigen::Vector3d& u, const Eigen::Vector3d& v);

/// The nearest of the 26 cube directions to unit vector `direction` (index
/// into CanonicalDirections()) and the angle to it (deg).
int NearestCube(const Eigen::Vector3d& direction, double* off_deg);

/// Per-axis noise pooled over the positions: sqrt(Σ (n_k − 1) s_k² /
/// Σ (n_k − 1)) (m/s²).
Eigen::Vector3d PooledNoise(std::span<const GuidePosition> positions);

/// The median of the positions' samples (the lower of two).
std::size_t MedianSamples(std::span<const GuidePosition> positions);

/// The target 1σ of each group: the options' where given, else the default
/// rule (record_guide.h) at `noise` and `samples` per hold.
std::array<double, 3> Targets(const Eigen::Vector3d& noise_std_mps2,
                              std::size_t samples,
                              const GuideOptions& options);

/// The cube direction to hold next (record_guide.h's rule), -1 when every
/// direction is held.
int NextTargetOf(std::span<const GuidePosition> positions,
                 const std::vector<bool>& held,
                 const Eigen::Vector3d& noise_std_mps2,
                 const std::array<double, 3>& target,
                 const GuideOptions& options);

/// The rotation vector (rad, body frame at the start) of the turn over
/// `time_s`, `gyro_radps` (the rows from the end of one position to the
/// start of the next), with the bias `bias_radps` taken out.
Eigen::Vector3d TurnRotation(std::span<const double> time_s,
                             std::span<const Eigen::Vector3d> gyro_radps,
                             const Eigen::Vector3d& bias_radps);

}  // namespace mpcal::internal
