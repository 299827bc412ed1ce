// ApplyCalibrationToBag (apply.h): the corrections of ApplyCalibration for a
// log in m/s² and rad/s, handed to the bag room's writer message by message.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "apply/apply_steps.h"
#include "mpcal/apply.h"
#include "mpcal/atomic_file.h"
#include "mpcal/bag.h"
#include "mpcal/error.h"

namespace mpcal {
namespace {

bool IsImuTopic(const BagTopic& t) {
  return t.type == "sensor_msgs/Imu" || t.type == "sensor_msgs/msg/Imu";
}

// The topic asked for, or the recording's only sensor_msgs/Imu topic.
std::string TopicToCorrect(const std::string& input, const std::string& topic) {
  if (!topic.empty()) return topic;
  std::vector<std::string> imu;
  for (const BagTopic& t : InspectBag(input).topics) {
    if (IsImuTopic(t)) imu.push_back(t.name);
  }
  if (imu.size() == 1) return imu.front();
  Advice advice;
  advice.settings = {{Option::kLogTopic, ""}};
  if (imu.empty()) {
    throw Error(ErrorKind::kInput, input + ": no sensor_msgs/Imu topic to correct");
  }
  throw Error(ErrorKind::kOption,
              fmt::format("{}: {} sensor_msgs/Imu topics ({}); one must be chosen",
                          input,
                          imu.size(),
                          fmt::join(imu, ", ")),
              advice);
}

}  // namespace

BagApplyResult ApplyCalibrationToBag(const Calibration& calibration,
                                     const std::string& input,
                                     const std::string& output,
                                     const BagApplyOptions& options) {
  RefuseOverwritingInput(input, output);
  BagApplyResult result;
  result.format = DetectBagFormat(input);
  // A recording's sensor_msgs/Imu is in m/s² and rad/s (REP 103); the
  // correctors are made before the recording is read, so that a calibration
  // that does not apply is refused at once.
  const Corrector correct(calibration, AccelUnits::kMps2, AccelUnits::kMps2);
  std::optional<GyroCorrector> correct_gyro;
  if (calibration.gyroscope) {
    correct_gyro.emplace(*calibration.gyroscope, GyroUnits::kRadps, GyroUnits::kRadps);
  }
  result.topic = TopicToCorrect(input, options.topic);
  internal::RestSummary rest(1.0);
  const ImuEdit edit = [&](ImuMessage& m) {
    if (!m.has_linear_acceleration) {
      ++result.unmeasured_messages;
      return;
    }
    const Eigen::Vector3d raw = m.linear_acceleration_mps2;
    m.linear_acceleration_mps2 = correct(raw);
    rest.Add(m.linear_acceleration_mps2, raw);
    if (correct_gyro && m.has_angular_velocity) {
      m.angular_velocity_radps =
          (*correct_gyro)(m.angular_velocity_radps, m.linear_acceleration_mps2);
      result.gyro_corrected = true;
    }
    ++result.corrected_messages;
  };
  BagRewriteResult written;
  WriteStreamAtomically(output, [&](std::ostream& out) {
    written = RewriteImuMessages(input, out, result.topic, edit, result.warnings);
    if (written.imu_messages == 0) {
      throw Error(
          ErrorKind::kInput,
          fmt::format("{}: topic '{}' holds no message to correct", input, result.topic));
    }
  });
  result.other_messages = written.other_messages;
  result.compressions = written.compressions;
  if (const std::optional<internal::Rest> at_rest = rest.Finish()) {
    result.rest_magnitude_mps2 = at_rest->magnitude_mps2;
    result.rest_mismatch = internal::CheckRestMagnitude(*at_rest,
                                                        calibration.gravity_mps2,
                                                        options.rest_tolerance,
                                                        AccelUnits::kMps2,
                                                        input);
  }
  return result;
}

}  // namespace mpcal
