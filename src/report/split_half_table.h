// The split-half check of a calibration (docs/method.md §9) as a table: each
// split, its halves, the z of every parameter, the RMS z and the verdict.
#pragma once

#include <string>

#include "mpcal/calibration.h"

namespace mpcal::report {

/// A heading, a note on how to read it, the table, and the widening of the
/// 1σ when the halves disagree.
std::string SplitHalfTable(const SplitHalfSummary& check, ModelKind model);

}  // namespace mpcal::report
