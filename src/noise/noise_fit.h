// Private to src/noise/: the term fit of one axis (noise_fit.cc), for
// noise.cc, and the cluster sizes of an Allan curve (allan.cc), for
// allan_sums.cc and the fit's record-length forecasts (term_measure.cc).
#pragma once

#include <cstdint>
#include <vector>

#include "mpcal/noise.h"

namespace mpcal::internal {

/// The cluster sizes m of a record of `samples` samples (log-spaced, allan.cc).
/// Each a multiple of its stride ClusterStride (1 below 2 min_overlaps).
std::vector<std::int64_t> ClusterSizes(std::int64_t samples, const AllanOptions& options);
/// Step between start indices at cluster size m: the largest power of two
/// at most m / min_overlaps (at least 1).
std::int64_t ClusterStride(std::int64_t m, const AllanOptions& options);

/// Terms, intervals and record-length advice of one axis from its Allan
/// curve; `phase_points` = samples + 1.
AxisNoise AnalyseAxis(std::vector<AllanPoint> curve,
                      double phase_points,
                      const NoiseOptions& options);

}  // namespace mpcal::internal
