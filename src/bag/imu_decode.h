// Private to src/bag/: sensor_msgs/Imu from its two serialisations.
#pragma once

#include <cstdint>
#include <string_view>

#include "mpcal/bag.h"

namespace mpcal::bag {

/// sensor_msgs/Imu's ROS 1 md5sum (the connection header's "md5sum").
inline constexpr std::string_view kRos1ImuMd5 = "6a62c6daae103f4ff57a132d6f95cec2";
inline constexpr std::string_view kRos1ImuType = "sensor_msgs/Imu";
inline constexpr std::string_view kRos2ImuType = "sensor_msgs/msg/Imu";

/// A ROS 1 serialised sensor_msgs/Imu (little endian, unpadded).
/// \throws DataError when the length does not fit the message.
ImuMessage DecodeRos1Imu(std::string_view data, std::int64_t receive_ns);

/// A CDR serialised sensor_msgs/msg/Imu: a 4-byte encapsulation header
/// (plain CDR, big or little endian), fields aligned to their size counted
/// from after the header.
/// \throws DataError for another encapsulation or a length that does not fit.
ImuMessage DecodeCdrImu(std::string_view data, std::int64_t receive_ns);

}  // namespace mpcal::bag
