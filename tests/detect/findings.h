// Helpers for tests that read the detect room's findings.
#pragma once

#include <string>
#include <vector>

#include "mpcal/advice.h"
#include "mpcal/coverage.h"
#include "mpcal/detect.h"

namespace mpcal::test {

// The findings as the plain sentences a library user reads.
template <typename T>
std::vector<std::string> Words(const std::vector<T>& findings) {
  std::vector<std::string> out;
  for (const auto& f : findings) out.push_back(Describe(f));
  return out;
}

// Whether the advice names `option`.
inline bool Names(const Advice& advice, Option option) {
  for (const auto& s : advice.settings) {
    if (s.option == option) return true;
  }
  return false;
}

}  // namespace mpcal::test
