// The format is told by the first bytes; each container has its own reader.
#include "mpcal/bag.h"

#include <filesystem>

#include "bag/bag_io.h"
#include "bag/bag_write.h"
#include "bag/mcap_bag.h"
#include "bag/mcap_records.h"
#include "bag/ros1_bag.h"
#include "bag/ros1_records.h"
#include "bag/ros2_bag.h"
#include "mpcal/error.h"

namespace mpcal {
namespace {

constexpr std::string_view kSqliteMagic{"SQLite format 3\0", 16};

// The first bytes as the message shows them: printable ASCII kept, the rest
// as \xNN.
std::string Shown(std::string_view bytes) {
  std::string out;
  for (const char ch : bytes) {
    const auto u = static_cast<unsigned char>(ch);
    if (u >= 0x20 && u < 0x7F) {
      out += ch;
    } else {
      static constexpr char kHex[] = "0123456789abcdef";
      out += "\\x";
      out += kHex[u >> 4];
      out += kHex[u & 0xF];
    }
  }
  return out;
}

}  // namespace

std::string_view ToString(BagFormat format) {
  switch (format) {
    case BagFormat::kRos1:
      return "ros1";
    case BagFormat::kMcap:
      return "mcap";
    case BagFormat::kRos2Sqlite:
      return "ros2-sqlite";
  }
  return "unknown";
}

BagFormat DetectBagFormat(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    if (std::filesystem::exists(std::filesystem::path(path) / "metadata.yaml", ec)) {
      return BagFormat::kRos2Sqlite;
    }
    throw Error(ErrorKind::kInput,
                path + ": a directory without metadata.yaml (not a ROS 2 bag)");
  }
  bag::BagFile file(path);
  const std::string head = file.ReadSome(0, 16);
  if (head.empty()) throw Error(ErrorKind::kInput, path + ": the file is empty");
  if (head.starts_with(bag::ros1::kMagic)) return BagFormat::kRos1;
  if (head.starts_with(bag::mcap::kMagic)) return BagFormat::kMcap;
  if (head.starts_with(kSqliteMagic)) return BagFormat::kRos2Sqlite;
  if (head.starts_with("#ROSBAG V")) {
    throw Error(ErrorKind::kInput,
                path + ": a ROS 1 bag of format " + Shown(head.substr(9, 3)) +
                    " (only 2.0 is read)");
  }
  throw Error(ErrorKind::kInput,
              path +
                  ": not a ROS 1 bag, an MCAP file or a ROS 2 bag (it "
                  "starts with '" +
                  Shown(head) + "')");
}

bool IsBag(const std::string& path) {
  if (path == "-") return false;
  try {
    DetectBagFormat(path);
    return true;
  } catch (const Error&) {
    return false;
  }
}

BagSummary InspectBag(const std::string& path) {
  switch (DetectBagFormat(path)) {
    case BagFormat::kRos1:
      return bag::InspectRos1(path);
    case BagFormat::kMcap:
      return bag::InspectMcap(path);
    case BagFormat::kRos2Sqlite:
      return bag::InspectRos2(path);
  }
  return {};
}

std::vector<BagTopic> ListBagTopics(const std::string& path) {
  if (DetectBagFormat(path) == BagFormat::kRos2Sqlite) {
    return bag::InspectRos2(path, /*count_messages=*/false).topics;
  }
  return InspectBag(path).topics;
}

void ReadImuMessages(const std::string& path,
                     const std::string& topic,
                     const ImuSink& sink,
                     std::vector<std::string>& warnings) {
  switch (DetectBagFormat(path)) {
    case BagFormat::kRos1:
      return bag::ReadRos1Imu(path, topic, sink, warnings);
    case BagFormat::kMcap:
      return bag::ReadMcapImu(path, topic, sink, warnings);
    case BagFormat::kRos2Sqlite:
      return bag::ReadRos2Imu(path, topic, sink, warnings);
  }
}

BagRewriteResult RewriteImuMessages(const std::string& input,
                                    std::ostream& output,
                                    const std::string& topic,
                                    const ImuEdit& edit,
                                    std::vector<std::string>& warnings,
                                    const ImuCovariances& covariances) {
  switch (DetectBagFormat(input)) {
    case BagFormat::kRos1:
      return bag::RewriteRos1(input, output, topic, edit, covariances, warnings);
    case BagFormat::kMcap:
      return bag::RewriteMcap(input, output, topic, edit, covariances, warnings);
    case BagFormat::kRos2Sqlite:
      break;
  }
  throw Error(ErrorKind::kInput,
              input +
                  ": a ROS 2 bag is read but not written; a ROS 1 bag or an MCAP file "
                  "can be (ros2 bag convert makes an MCAP file of it)");
}

}  // namespace mpcal
