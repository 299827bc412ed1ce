// The turns' weights beyond the accelerometer's noise: the gyroscope's white
// noise told apart from the hand's tremor, the bias's walk, and which
// measure of the gravity directions the turns use, the plain mean of a
// direction window or the one carried by the gyroscope, by which of the two
// errs less on this session.
#pragma once

#include <span>

#include "mpcal/calibration.h"
#include "mpcal/detect.h"
#include "mpcal/gyro.h"
#include "mpcal/recording.h"
#include "mpcal/recording_view.h"
#include "turn_problem.h"

namespace mpcal::internal {

/// The gyroscope's white noise per sample (raw units): the median over the
/// positions of the RMS second difference over √6. The scatter at rest
/// (TurnProblem::noise_std_raw) also holds the hand's tremor, which is motion
/// the integration follows, not noise; the second difference passes white
/// noise (variance 6σ²) and damps slow motion. Zero with no position of 3
/// samples.
double WhiteNoiseStd(const RecordingView& recording,
                     std::span<const StaticInterval> intervals);

/// Chooses the turns' directions (GyroDirections) and adds the chosen
/// measure's error to their weights. The carried mean of a window of W
/// seconds holds, per tangent component, σ² dt W/3 of the gyroscope's white
/// noise (σ per sample: `white_std_raw` at the nominal scale
/// `radps_per_unit`; the mean over [0, W] of an angle random walk pinned at
/// the edge); the plain mean holds the sway's angle instead, of variance
/// v_s. Their difference holds both, so over the edges E[|d|²/2] = v_s +
/// mean(σ² dt W/3): v_s is estimated from that, and the plain mean is kept
/// unless v_s exceeds the carried mean's noise. No change with no scale.
GyroDirections ChooseDirections(double white_std_raw,
                                double radps_per_unit,
                                TurnProblem* problem);

/// Sets every turn's gyroscope variance (turn_problem.h sets it from the
/// scatter at rest) with the white noise and the bias's walk, and chooses
/// its directions (GyroDirections); `radps_per_unit` is the nominal scale
/// the directions were carried at (0: not carried, the plain means).
GyroDirections WeighTurns(const RecordingView& recording,
                          std::span<const StaticInterval> intervals,
                          const Calibration& accel,
                          double radps_per_unit,
                          TurnProblem* problem);

}  // namespace mpcal::internal
