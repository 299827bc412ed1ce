// Applying a calibration: the magnitude-at-rest finding in the words a
// command-line user reads (the library gives the kind, the figures and the
// units to read the log in).
#pragma once

#include <string>

#include "mpcal/apply.h"

namespace mpcal::cli {

/// "a.csv: the corrected magnitude at rest is ...; the log looks like it is
/// in g: use --units g".
std::string ExplainRestMismatch(const RestMismatch& mismatch);

}  // namespace mpcal::cli
