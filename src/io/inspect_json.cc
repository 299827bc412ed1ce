// The inspection as JSON (mpcal.inspection/1): facts only, every figure with
// its unit in its name or beside it.
#include <string>

#include <nlohmann/json.hpp>

#include "mpcal/inspect.h"

namespace mpcal {
namespace {

using json = nlohmann::ordered_json;

json Vector(const Eigen::Vector3d& v) { return json::array({v.x(), v.y(), v.z()}); }

json RangeJson(const ReadingRange& r) {
  if (r.count == 0) return nullptr;
  json j;
  j["count"] = r.count;
  j["min"] = Vector(r.min);
  j["max"] = Vector(r.max);
  j["mean_magnitude"] = r.mean_norm();
  return j;
}

std::string AccelLookName(AccelUnitsLook look) {
  switch (look) {
    case AccelUnitsLook::kNotJudged:
      return "not_judged";
    case AccelUnitsLook::kFits:
      return "fits";
    case AccelUnitsLook::kLikeG:
      return "g";
    case AccelUnitsLook::kLikeMps2:
      return "mps2";
    case AccelUnitsLook::kLikeCounts:
      return "counts";
    case AccelUnitsLook::kNeither:
      return "neither";
  }
  return "not_judged";
}

std::string GyroLookName(GyroUnitsLook look) {
  switch (look) {
    case GyroUnitsLook::kNotJudged:
      return "not_judged";
    case GyroUnitsLook::kFits:
      return "fits";
    case GyroUnitsLook::kLikeDps:
      return "dps";
    case GyroUnitsLook::kLikeCounts:
      return "counts";
  }
  return "not_judged";
}

json OrderJson(const TimeOrderCount& order) {
  return {{"out_of_order", order.out_of_order}, {"worst_back_s", order.worst_back_s}};
}

json RecordingJson(const Inspection& in) {
  json topics = json::array();
  for (const BagTopic& t : in.bag.topics) {
    topics.push_back({{"name", t.name},
                      {"type", t.type},
                      {"encoding", t.encoding},
                      {"messages", t.messages},
                      {"first_receive_ns", t.first_ns},
                      {"last_receive_ns", t.last_ns},
                      {"rate_hz", TopicRateHz(t)}});
  }
  json imu = json::array();
  for (const ImuTopicInspection& t : in.imu) {
    json j;
    j["topic"] = t.topic;
    j["messages"] = t.messages;
    j["first_stamp_ns"] = t.first_stamp_ns;
    j["last_stamp_ns"] = t.last_stamp_ns;
    j["rate_hz"] = t.rate_hz;
    j["stamp_order"] = OrderJson(t.stamp_order);
    j["receive_order"] = OrderJson(t.receive_order);
    j["accel_mps2"] = RangeJson(t.accel_mps2);
    j["gyro_radps"] = RangeJson(t.gyro_radps);
    j["accel_units_look"] = AccelLookName(t.accel_look);
    j["gyro_units_look"] = GyroLookName(t.gyro_look);
    imu.push_back(std::move(j));
  }
  json j;
  j["container"] = std::string(ToString(in.bag.format));
  j["compressions"] = in.bag.compressions;
  j["topics"] = std::move(topics);
  j["imu_topics"] = std::move(imu);
  return j;
}

json TextLogJson(const LogInspection& log) {
  const LogLayout& l = log.layout;
  json j;
  j["columns"] = l.column_names;
  j["header_line"] = l.header_line;
  j["time_column"] = l.time_column >= 0 ? json(l.time_column) : json(nullptr);
  j["accel_columns"] = l.accel_columns;
  j["gyro_columns"] = l.has_gyro() ? json(l.gyro_columns) : json(nullptr);
  j["time_unit"] = std::string(ToString(l.time_unit));
  j["accel_units"] = std::string(ToString(log.units));
  j["gyro_units"] = std::string(ToString(log.gyro_units));
  j["rows"] = log.rows;
  j["first_time_s"] = log.first_time_s;
  j["last_time_s"] = log.last_time_s;
  j["rate_hz"] = log.rate_hz;
  j["time_not_increasing"] = log.time_not_increasing;
  j["accel"] = RangeJson(log.accel);
  j["gyro"] = RangeJson(log.gyro);
  j["accel_units_look"] = AccelLookName(log.accel_look);
  j["gyro_units_look"] = GyroLookName(log.gyro_look);
  return j;
}

}  // namespace

std::string InspectionJson(const Inspection& in) {
  json j;
  j["format"] = "mpcal.inspection/1";
  j["input"] = in.source;
  j["recording"] = in.is_recording ? RecordingJson(in) : json(nullptr);
  j["text_log"] = in.is_recording ? json(nullptr) : TextLogJson(in.log);
  json warnings = in.warnings;
  for (const std::string& w : in.bag.warnings) warnings.push_back(w);
  j["warnings"] = std::move(warnings);
  return j.dump(2) + "\n";
}

}  // namespace mpcal
