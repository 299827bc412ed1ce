// The gyroscope bias's random walk between the static positions: how much
// of it the linear interpolation of the rest biases across a turn leaves in
// the turn's integrated angle, and its density estimated from the rest
// biases themselves, so that each turn's weight holds it.
#pragma once

#include <span>

#include "mpcal/calibration.h"
#include "mpcal/detect.h"
#include "mpcal/recording.h"
#include "mpcal/recording_view.h"
#include "turn_problem.h"

namespace mpcal::internal {

/// Variance (s³ per unit of walk density², i.e. per (unit/s)²/Hz) of the
/// integral over [s0_s, s1_s] of a unit Brownian bridge pinned to zero at
/// `pin_a_s` and `pin_b_s`: the angle left in a turn by interpolating a
/// random-walk bias linearly between two positions' centres. Times outside
/// the pins are clamped to them.
double BridgeIntegralVariance(double pin_a_s, double pin_b_s, double s0_s, double s1_s);

/// The bias's random-walk density squared per axis (raw units²/s), by the
/// method of moments on the changes of the rest bias between consecutive
/// positions: each change holds the walk over the positions' centres (less
/// a sixth of each position's length, which its mean averages) and the
/// white noise of the two means; a steady drift, which the interpolation
/// follows, is removed first. Zero when the changes are no larger than the
/// white noise explains, or with fewer than three positions.
double EstimateBiasWalk(const TurnProblem& problem,
                        std::span<const StaticInterval> intervals,
                        const RecordingView& recording,
                        const Calibration& accel);

/// Adds to every turn's gyroscope variance the walk `walk_raw2_per_s` left
/// by the interpolation between its two positions' centres.
void AddBiasWalk(double walk_raw2_per_s, TurnProblem* problem);

}  // namespace mpcal::internal
