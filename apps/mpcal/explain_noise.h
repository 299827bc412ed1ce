// The noise model held against the Allan curve, in words (ModelCheck).
#pragma once

#include <string>

#include "mpcal/noise.h"

namespace mpcal::cli {

/// One table cell: "fits: 2 of 61 outside", "MISSES: 55 of 61 outside".
std::string ModelCheckCell(const ModelCheck& check);

/// The axes of a sensor where the model misses the curve (with their τ
/// ranges) and those whose short-τ end was cut off, one line each, on
/// standard output; nothing when the model fits every axis from its start.
void PrintModelCheck(const SensorNoise& sensor, bool gyro, double confidence);

}  // namespace mpcal::cli
