// The bag fixtures' place (tests/data/bags/), shared by the bag tests.
#pragma once

#include <string>

#include "test_util.h"

namespace mpcal::testing {

inline std::string Bag(const std::string& name) { return TestDataPath("bags/" + name); }

}  // namespace mpcal::testing
