// libFuzzer target for the ROS 1 bag reader (format 2.0). The input is the
// file (with the magic put in front when it lacks it), written to an
// in-memory file opened by its /proc path, so the reader runs exactly as on
// a file from disk; it is inspected, its /imu/data topic read, then
// rewritten as `apply` does and read back.
#include <cstddef>
#include <cstdint>

#include "bag_input.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string path = mpcal::fuzz::WriteWithMagic("#ROSBAG V2.0\n", data, size);
  mpcal::fuzz::ReadBagChecked(path);
  mpcal::fuzz::RewriteChecked(path);
  return 0;
}
