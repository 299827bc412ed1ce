// The repeatability room's refusals in the words the `mpcal repeat` user
// reads: trials that do not compare are refused with the advice to calibrate
// every session with the same settings, spelled as flags.
#pragma once

#include <string>

#include "mpcal/error.h"

namespace mpcal::cli {

/// "...: trials must share one model (calibrate every session with the same
/// --model)": the error's sentence and, when its advice is to calibrate with
/// the same settings (Stage::kCalibrate), those flags ("--gravity or
/// --latitude/--height"); otherwise Explain(error).
std::string ExplainRepeatRefusal(const Error& error);

}  // namespace mpcal::cli
