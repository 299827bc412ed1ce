// Checks (mpcal/check.h) as the lines a user reads: one
// per check, its name, the verdict (coloured on a terminal) and why in a
// few words.
#pragma once

#include <cstdio>
#include <string>
#include <vector>

#include "mpcal/check.h"

namespace mpcal::cli {

/// Why, in a few words: "residuals as the sensor noise explains (variance
/// factor 1.02)".
std::string ExplainCheck(const Check& check);

/// "checks:" then a line per check, coloured for `stream`.
std::string FormatChecks(const std::vector<Check>& checks, std::FILE* stream);

}  // namespace mpcal::cli
