// The rotation of one turn between two captured positions, integrated by
// the gyroscope room's own integration with the bias measured at the
// position before (record_guide.h: which axes the turns have excited).
#include <Eigen/Geometry>

#include "guide_steps.h"
#include "mpcal/gyro.h"
#include "mpcal/gyro_calibration.h"
#include "mpcal/recording.h"

namespace mpcal::internal {

Eigen::Vector3d TurnRotation(std::span<const double> time_s,
                             std::span<const Eigen::Vector3d> gyro_radps,
                             const Eigen::Vector3d& bias_radps) {
  if (time_s.size() < 2 || gyro_radps.size() != time_s.size()) {
    return Eigen::Vector3d::Zero();
  }
  Recording turn;
  turn.source = "turn";
  turn.time_s.assign(time_s.begin(), time_s.end());
  turn.gyro_radps.assign(gyro_radps.begin(), gyro_radps.end());
  turn.accel.assign(time_s.size(), Eigen::Vector3d::Zero());
  GyroCalibration nominal;
  nominal.bias_radps = bias_radps;
  const Eigen::Matrix3d r = IntegrateRotation(turn, 0, turn.size() - 1, nominal);
  const Eigen::AngleAxisd aa(r);
  return aa.axis() * aa.angle();
}

}  // namespace mpcal::internal
