// Private to src/bag/: InspectBag and ReadImuMessages for ROS 1 bags.
#pragma once

#include <string>
#include <vector>

#include "mpcal/bag.h"

namespace mpcal::bag {

BagSummary InspectRos1(const std::string& path);
void ReadRos1Imu(const std::string& path,
                 const std::string& topic,
                 const ImuSink& sink,
                 std::vector<std::string>& warnings);

/// "/a (type), /b (type)": the topics a recording holds, for messages that
/// refuse a topic.
std::string ListTopics(const std::vector<BagTopic>& topics);

/// Hands the messages over in batches of a bounded size.
class ImuBatcher {
 public:
  explicit ImuBatcher(const ImuSink& sink) : sink_(sink) {}
  void Add(const ImuMessage& m) {
    batch_.push_back(m);
    ++count_;
    if (batch_.size() >= kBatch) Flush();
  }
  void Flush() {
    if (!batch_.empty() && sink_) sink_(batch_);
    batch_.clear();
  }
  std::size_t count() const { return count_; }

 private:
  static constexpr std::size_t kBatch = 4096;
  const ImuSink& sink_;
  std::vector<ImuMessage> batch_;
  std::size_t count_ = 0;
};

}  // namespace mpcal::bag
