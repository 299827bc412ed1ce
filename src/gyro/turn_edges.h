// Where each turn's motion starts and stops. Detection keeps a position's
// samples away from the motion on either side by half its window and a
// settling time (detect.h: about 0.8 s at each end by default), which the
// accelerometer's mean wants; a turn integrated over that still time only
// gathers the gyroscope's white noise and the bias's walk. The gyroscope and
// the accelerometer together tell, sample by sample, where the sensor is
// still at rest.
#pragma once

#include <span>
#include <vector>

#include "mpcal/detect.h"
#include "mpcal/recording.h"

namespace mpcal::internal {

/// Each position's interval with its end moved forward and the next one's
/// begin moved back for as long as both sensors stay at rest: as long as the
/// mean over a short window ahead of the edge (about 50 ms) of each reading's
/// departure from its position's mean stays within the noise, judged by χ²
/// over the six axes against the position's own scatter (or the median
/// position's, when larger). Only `begin`, `end`, `start_s` and `end_s`
/// change: the means and scatters stay the detected ones. A position never
/// reaches past its neighbour's edge. Needs gyroscope readings.
std::vector<StaticInterval> ExtendToMotion(const Recording& recording,
                                           std::span<const StaticInterval> intervals);

}  // namespace mpcal::internal
