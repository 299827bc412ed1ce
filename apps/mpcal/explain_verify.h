// The field verification's findings in the words a command-line user reads
// (the library gives the kind, the figures and the advice as facts).
#pragma once

#include <string>

#include "mpcal/verify.h"

namespace mpcal::cli {

/// The finding's sentence with its advice in flags: "...; if the clocks
/// differ, pass --time-align motion or --time-offset".
std::string ExplainVerifyFinding(const VerifyFinding& finding);

}  // namespace mpcal::cli
