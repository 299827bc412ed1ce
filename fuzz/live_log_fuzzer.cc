// libFuzzer target for the live stream's parser (LiveLogParser): a stream
// cut at any point parses as the whole one (live_log_input.h says how an
// input becomes a stream and what must hold). Any outcome but success or
// mpcal::Error, the same in every piecing, is a finding: an exception of
// another type, a sanitizer report, or a broken invariant (abort).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "live_log_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string problem = mpcal::fuzz::CheckLiveLogInput(data, size);
  if (!problem.empty()) {
    std::fprintf(stderr, "invariant broken: %s\n", problem.c_str());
    std::abort();
  }
  return 0;
}
