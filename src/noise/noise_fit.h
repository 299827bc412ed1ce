// The term fit of one axis (noise_fit.cc), for noise.cc.
#pragma once

#include <vector>

#include "mpcal/noise.h"

namespace mpcal::internal {

/// Terms, intervals and record-length advice of one axis from its Allan
/// curve; `phase_points` = samples + 1.
AxisNoise AnalyseAxis(std::vector<AllanPoint> curve,
                      double phase_points,
                      const NoiseOptions& options);

}  // namespace mpcal::internal
