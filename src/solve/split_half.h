// The split-half check (docs/method.md §9): the used positions split in two, by
// time and alternately, each half calibrated alone, and the two estimates
// compared against their combined 1σ. Two halves of one session are two
// calibrations of the same sensor at the same power-up, so their
// difference over its 1σ is standard normal when the 1σ is honest; it is
// the user's evidence on their own recording, with no truth needed.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "mpcal/calibration.h"
#include "mpcal/solve.h"

namespace mpcal::internal {

/// Calibrates both halves of each split of the used positions with
/// `options` (no cross-validation, no split-half check of their own) and
/// compares them. A split is not `determined` when a half leaves a
/// parameter undetermined or its fit fails. `widening` is √(χ²/dof) of the
/// worst split whose χ² test rejects, else 1; the tests share
/// options.split_half_significance (each of n determined splits is tested at
/// significance/n), so that it is the rate at which an honest session is
/// widened.
SplitHalfSummary CheckSplitHalves(std::span<const PositionObservation> positions,
                                  const std::vector<bool>& used,
                                  const SolveOptions& options);

/// Marks the determined `comparisons` that disagree beyond chance, each
/// tested at `significance` over their number (so that `significance` is the
/// rate at which a session with honest 1σ has any split disagree), and
/// returns the widening: √(χ²/dof) of the worst that disagrees, else 1.
double JudgeSplits(std::vector<SplitHalfComparison>& comparisons, double significance);

/// The interleaved split: indices (into `positions`, ascending) of each
/// half. Positions are paired by nearest orientation in recording order and
/// each pair shared between the halves, so that both span the sphere as the
/// whole does whatever the order the positions were held in (an up/down
/// pair held in turn would otherwise put every "up" in one half).
std::array<std::vector<std::size_t>, 2> InterleavedHalves(
    std::span<const PositionObservation> positions);

}  // namespace mpcal::internal
