// Private to src/bag/: ROS 2 bags, a directory with metadata.yaml and its
// storage files (SQLite *.db3 or *.mcap), or a lone *.db3 file.
#pragma once

#include <string>
#include <vector>

#include "mpcal/bag.h"

namespace mpcal::bag {

/// The storage files of a ROS 2 bag in order (the `_N` suffix's number), or
/// `path` itself when it is a file.
/// \throws mpcal::Error for a directory without *.db3 or *.mcap files.
std::vector<std::string> Ros2StorageFiles(const std::string& path);

/// With `count_messages` false, a SQLite file's topics are listed from its
/// topics table alone (messages, first_ns and last_ns left 0): counting
/// them is a pass over every message.
BagSummary InspectRos2(const std::string& path, bool count_messages = true);
void ReadRos2Imu(const std::string& path,
                 const std::string& topic,
                 const ImuSink& sink,
                 std::vector<std::string>& warnings);

}  // namespace mpcal::bag
