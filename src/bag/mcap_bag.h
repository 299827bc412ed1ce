// Private to src/bag/: InspectBag and ReadImuMessages for MCAP files.
#pragma once

#include <string>
#include <vector>

#include "mpcal/bag.h"

namespace mpcal::bag {

BagSummary InspectMcap(const std::string& path);
void ReadMcapImu(const std::string& path,
                 const std::string& topic,
                 const ImuSink& sink,
                 std::vector<std::string>& warnings);

}  // namespace mpcal::bag
