// ApplyCalibrationToBag (apply.h): the corrections of ApplyCalibration for a
// log in m/s² and rad/s, handed to the bag room's writer message by message.
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <system_error>
#include <vector>

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

// The topic's message rate (Hz) from the recording's index (its receive
// times), which the per-sample variance N²·f needs.
double MessageRateHz(const std::string& input, const std::string& topic) {
  for (const BagTopic& t : InspectBag(input).topics) {
    if (t.name != topic) continue;
    if (t.messages >= 2 && t.last_ns > t.first_ns) {
      return static_cast<double>(t.messages - 1) /
             (static_cast<double>(t.last_ns - t.first_ns) * 1e-9);
    }
  }
  throw Error(ErrorKind::kInput,
              fmt::format("{}: topic '{}' has no message rate (fewer than 2 messages, "
                          "or no time between its first and last) to turn a white "
                          "noise density into a variance per sample",
                          input,
                          topic));
}

// The covariances BagApplyOptions asks for: N²·f per axis.
ImuCovariances CovariancesFor(const BagApplyOptions& options,
                              const std::string& input,
                              const std::string& topic,
                              std::optional<double>& rate_hz) {
  ImuCovariances covariances;
  if (!options.accel_white_noise_mps2_per_rthz &&
      !options.gyro_white_noise_radps_per_rthz) {
    return covariances;
  }
  rate_hz = MessageRateHz(input, topic);
  if (options.accel_white_noise_mps2_per_rthz) {
    covariances.linear_acceleration_m2ps4 =
        options.accel_white_noise_mps2_per_rthz->cwiseAbs2() * *rate_hz;
  }
  if (options.gyro_white_noise_radps_per_rthz) {
    covariances.angular_velocity_rad2ps2 =
        options.gyro_white_noise_radps_per_rthz->cwiseAbs2() * *rate_hz;
  }
  return covariances;
}

// A damaged input can hold records the writer copies as they are but a
// reader takes differently once they stand in a whole file (a message the
// first reading never reached as an IMU message, say). The corrected file is
// read back as any reader would: every message the writer corrected, no
// other, or it is removed and refused, never left to be read as corrected.
void RefuseUnlessReadBackWhole(const std::string& input,
                               const std::string& output,
                               const std::string& topic,
                               std::int64_t written) {
  std::int64_t read_back = 0;
  std::string why;
  try {
    std::vector<std::string> warnings;
    ReadImuMessages(
        output,
        topic,
        [&](std::span<const ImuMessage> batch) {
          read_back += static_cast<std::int64_t>(batch.size());
        },
        warnings);
  } catch (const Error& e) {
    why = e.what();
  }
  if (why.empty() && read_back == written) return;
  std::error_code ignored;
  std::filesystem::remove(output, ignored);
  if (why.empty()) {
    why = fmt::format("{} IMU messages read back, {} corrected", read_back, written);
  }
  throw Error(ErrorKind::kInput,
              fmt::format("{}: the corrected recording does not read back whole ({}): "
                          "the input is damaged where its records disagree; nothing "
                          "written",
                          input,
                          why));
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
  result.covariances =
      CovariancesFor(options, input, result.topic, result.covariance_rate_hz);
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
    written = RewriteImuMessages(
        input, out, result.topic, edit, result.warnings, result.covariances);
    if (written.imu_messages == 0) {
      throw Error(
          ErrorKind::kInput,
          fmt::format("{}: topic '{}' holds no message to correct", input, result.topic));
    }
  });
  RefuseUnlessReadBackWhole(input, output, result.topic, written.imu_messages);
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
