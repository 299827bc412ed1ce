// sensor_msgs/Imu: header, orientation (4 f64) and its covariance (9),
// angular_velocity (3) and covariance (9), linear_acceleration (3) and
// covariance (9). The ROS 1 layout is the message definition's fields in
// order with no padding (wiki.ros.org/msg "Serialization"); the CDR layout
// (OMG DDS-XTypes / CDR as ROS 2's rmw implementations write it) aligns
// each primitive to its size from the end of the encapsulation header.
#include "bag/imu_decode.h"

#include <string>

#include "bag/bag_io.h"

namespace mpcal::bag {
namespace {

constexpr std::int64_t kNsPerS = 1'000'000'000;

Eigen::Vector3d Vec3(ByteCursor& c, bool big_endian) {
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) v[i] = c.Read<double>("a vector component", big_endian);
  return v;
}

// Orientation, covariances, and the two vectors the calibration needs; the
// caller has read the header and aligned the cursor.
// A covariance whose first element is -1 marks the quantity as not measured.
bool Given(ByteCursor& c, bool big_endian, const char* what) {
  const double first = c.Read<double>(what, big_endian);
  c.Skip(8 * 8, what);
  return first != -1.0;
}

void ReadBody(ByteCursor& c, bool big_endian, ImuMessage& m) {
  c.Skip(8 * (4 + 9), "orientation and its covariance");
  m.angular_velocity_radps = Vec3(c, big_endian);
  m.has_angular_velocity = Given(c, big_endian, "angular_velocity_covariance");
  m.linear_acceleration_mps2 = Vec3(c, big_endian);
  m.has_linear_acceleration = Given(c, big_endian, "linear_acceleration_covariance");
  if (!c.empty()) {
    throw DataError("a sensor_msgs/Imu message with " + std::to_string(c.remaining()) +
                    " bytes after its last field");
  }
}

}  // namespace

ImuMessage DecodeRos1Imu(std::string_view data, std::int64_t receive_ns) {
  ByteCursor c(data);
  ImuMessage m;
  m.receive_ns = receive_ns;
  c.U32("header.seq");
  const std::uint32_t sec = c.U32("header.stamp.sec");
  const std::uint32_t nsec = c.U32("header.stamp.nsec");
  m.stamp_ns = static_cast<std::int64_t>(sec) * kNsPerS + nsec;
  c.Skip(c.U32("header.frame_id length"), "header.frame_id");
  ReadBody(c, false, m);
  return m;
}

ImuMessage DecodeCdrImu(std::string_view data, std::int64_t receive_ns) {
  ByteCursor c(data);
  if (c.U8("the encapsulation header") != 0)
    throw DataError("not a plain CDR encapsulation");
  const std::uint8_t kind = c.U8("the encapsulation header");
  if (kind > 1) {
    throw DataError("CDR encapsulation kind " + std::to_string(kind) +
                    " (only plain CDR, 0 big endian and 1 little endian, is read)");
  }
  const bool big = kind == 0;
  c.Skip(2, "the encapsulation options");
  const std::size_t origin = c.offset();
  ImuMessage m;
  m.receive_ns = receive_ns;
  const auto sec = c.Read<std::int32_t>("header.stamp.sec", big);
  const auto nanosec = c.Read<std::uint32_t>("header.stamp.nanosec", big);
  m.stamp_ns = static_cast<std::int64_t>(sec) * kNsPerS + nanosec;
  const auto frame_len = c.Read<std::uint32_t>("header.frame_id length", big);
  c.Skip(frame_len, "header.frame_id");
  c.Align(8, origin, "padding before orientation");
  ReadBody(c, big, m);
  return m;
}

}  // namespace mpcal::bag
