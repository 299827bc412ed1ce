// The simulated positions the solver's tests share: their noise and length.
#pragma once

#include <cstddef>

#include <Eigen/Core>

namespace mpcal::testing {

inline constexpr std::size_t kSamples = 1000;
inline const Eigen::Vector3d kNoise(0.02, 0.025, 0.03);  // m/s² per sample

}  // namespace mpcal::testing
