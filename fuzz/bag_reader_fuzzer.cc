// libFuzzer target for the bag readers (ROS 1, MCAP, ROS 2 SQLite).
//
// The input is the file. It goes through an in-memory file (memfd) opened by
// its /proc path, so the readers run exactly as on a file from disk. Each
// input is inspected, then its /imu/data topic read. Any outcome but success
// or mpcal::Error is a finding: another exception, a sanitizer report, a
// timeout or memory beyond the limit (every length is checked against what
// remains and the caps in bag.h), or a batch that breaks the sink's contract.
// The writer's walk over the input (RewriteImuMessages, as `apply` runs it)
// is fuzzed the same way, and what it writes must read back whole: every
// message it edited, with no warning.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <span>
#include <sstream>
#include <string>
#include <vector>

#include "memory_file.h"
#include "mpcal/bag.h"
#include "mpcal/error.h"

using mpcal::fuzz::Check;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = mpcal::fuzz::WriteMemoryFile(data, size);
  try {
    const mpcal::BagSummary summary = mpcal::InspectBag(path);
    for (const mpcal::BagTopic& t : summary.topics)
      Check(t.messages >= 0 && t.first_ns <= t.last_ns, "a count and a time range");
  } catch (const mpcal::Error&) {
    // The documented way to reject an input.
  }
  try {
    std::vector<std::string> warnings;
    std::size_t messages = 0;
    mpcal::ReadImuMessages(
        path,
        "/imu/data",
        [&](std::span<const mpcal::ImuMessage> batch) {
          Check(!batch.empty(), "a batch holds messages");
          messages += batch.size();
        },
        warnings);
    Check(messages <= size, "no more messages than bytes");
  } catch (const mpcal::Error&) {
  }
  std::stringstream rewritten;
  mpcal::BagRewriteResult written;
  try {
    std::vector<std::string> warnings;
    written = mpcal::RewriteImuMessages(
        path,
        rewritten,
        "/imu/data",
        [](mpcal::ImuMessage& m) { m.linear_acceleration_mps2.x() += 1.0; },
        warnings);
  } catch (const mpcal::Error&) {
    return 0;
  }
  const std::string bytes = rewritten.str();
  // The one in-memory file takes the output: the input has been read whole.
  const std::string out = mpcal::fuzz::WriteMemoryFile(bytes.data(), bytes.size());
  std::vector<std::string> warnings;
  std::int64_t read_back = 0;
  mpcal::ReadImuMessages(
      out,
      "/imu/data",
      [&](std::span<const mpcal::ImuMessage> batch) {
        read_back += static_cast<std::int64_t>(batch.size());
      },
      warnings);
  Check(read_back == written.imu_messages, "the rewritten messages read back");
  Check(warnings.empty() || written.imu_messages == 0, "the rewritten file is whole");
  return 0;
}
