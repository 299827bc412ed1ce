/// \file verdict.h
/// \brief A calibration's checks judged: for each (the fit, the positions,
/// the bias drift, the split-half check, the units, the gyroscope) whether
/// the result can be used as it is, deserves a look, or must not be used,
/// with the finding and the figures behind it (mpcal/check.h). The judgement
/// is the one the estimator already makes (SolveOptions' outlier threshold
/// and significances, the observability analysis, GyroFindingKind); the
/// words belong to the caller.
#pragma once

#include <vector>

#include "mpcal/calibrate.h"
#include "mpcal/check.h"

namespace mpcal {

/// The variance factor's χ² test is made at this significance: the 1 % of
/// the estimator's other tests (the split-half check, the bias drift).
inline constexpr double kFitSignificance = 0.01;

/// The fit, positions, bias drift, split-half and units checks, in that
/// order, and the gyroscope's when the recording had a gyroscope. `options` are the ones
/// `result` came from.
std::vector<Check> JudgeCalibration(const CalibrateResult& result,
                                    const CalibrateOptions& options);

}  // namespace mpcal
