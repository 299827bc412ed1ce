// What the bag fuzz targets share: the recording at `path` inspected, then
// its /imu/data topic read, then (ROS 1 and MCAP, the kinds `apply` writes)
// rewritten as `apply` does, and what is written read back whole. Any outcome but success
// or mpcal::Error is a finding: another exception, a sanitizer report, a timeout or
// memory beyond the limit (every length is checked against what remains and the caps in
// bag.h), or a batch that breaks the sink's contract.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "memory_file.h"
#include "mpcal/bag.h"
#include "mpcal/error.h"

namespace mpcal::fuzz {

/// `bytes` as the in-memory file's content, with `magic` in front unless
/// they begin with it, so that every input reaches the reader the target is
/// for (a mutated magic would only meet DetectBagFormat's refusal).
inline std::string WriteWithMagic(std::string_view magic,
                                  const void* data,
                                  std::size_t size) {
  const std::string_view bytes(static_cast<const char*>(data), size);
  if (bytes.starts_with(magic)) return WriteMemoryFile(data, size);
  std::string whole(magic);
  whole.append(bytes);
  return WriteMemoryFile(whole.data(), whole.size());
}

/// Inspects the recording at `path` and reads its /imu/data topic; at most
/// `max_messages` messages may come out (a compressed chunk can unpack to
/// far more messages than its bytes, so the container targets pass no bound).
inline void ReadBagChecked(const std::string& path,
                           std::size_t max_messages = static_cast<std::size_t>(-1)) {
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
    Check(messages <= max_messages, "no more messages than the input can hold");
  } catch (const mpcal::Error&) {
  }
}

/// Walks the recording at `path` as `apply` does (RewriteImuMessages, every
/// IMU message edited) and reads what it writes back, as `apply` does before
/// it keeps it: the writer copies what a reader reads, so every message it
/// edited, and no other, must come back, with no error. A copy that reads
/// otherwise is a finding (`apply` would refuse it, but only after writing it).
inline void RewriteChecked(const std::string& path) {
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
    return;
  }
  const std::string bytes = rewritten.str();
  // The one in-memory file takes the output: the input has been read whole.
  const std::string out = WriteMemoryFile(bytes.data(), bytes.size());
  std::vector<std::string> warnings;
  std::int64_t read_back = 0;
  bool read = true;
  try {
    mpcal::ReadImuMessages(
        out,
        "/imu/data",
        [&](std::span<const mpcal::ImuMessage> batch) {
          Check(!batch.empty(), "a batch holds messages");
          read_back += static_cast<std::int64_t>(batch.size());
        },
        warnings);
  } catch (const mpcal::Error&) {
    read = false;
  }
  Check(read, "the copy reads back without an error");
  Check(read_back == written.imu_messages, "the copy reads back every edited message");
}

}  // namespace mpcal::fuzz
