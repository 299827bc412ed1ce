// The turns of a recording scored with a gyroscope calibration that is
// already known (from a file): for the report, which shows the turn
// residuals before and after calibration without solving again.
#include <Eigen/Geometry>

#include "mpcal/gyro.h"
#include "rotation.h"
#include "turn_problem.h"
#include "turn_weights.h"

namespace mpcal {

std::vector<GyroTurn> ScoreGyroTurns(const RecordingView& recording,
                                     std::span<const StaticInterval> intervals,
                                     const Calibration& accel,
                                     const GyroCalibration& gyro) {
  const double scale = internal::HeldRadpsPerUnit(recording, gyro);
  const GyroOptions defaults;
  internal::TurnProblem problem = internal::BuildTurnProblem(
      recording,
      intervals,
      accel,
      defaults.direction_window_s,
      gyro.g_sensitivity_radps_per_mps2 ? GSensitivity::kOn : GSensitivity::kOff,
      defaults.g_sensitivity_min_f,
      scale);
  // The same directions and weights as the fit chose (gyro_solve.cc).
  internal::WeighTurns(recording, intervals, accel, scale, &problem);
  const Eigen::Matrix3d nominal = scale * Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d calibrated = scale * gyro.m;
  std::vector<GyroTurn> turns;
  for (const internal::TurnData& t : problem.turns) {
    GyroTurn turn;
    turn.from_position = t.from_position;
    turn.begin = t.begin;
    turn.end = t.end;
    turn.start_s = t.start_s;
    turn.end_s = t.end_s;
    turn.sigma_rad = t.Sigma(scale);
    turn.residual_before_rad =
        internal::TurnTilt(t, internal::TurnResidual(t, nominal, nullptr, nullptr));
    const Eigen::Matrix3d r = internal::TurnResidual(t, calibrated, nullptr, nullptr);
    turn.residual_after_rad = internal::TurnTilt(t, r);
    const Eigen::AngleAxisd aa(r);
    turn.angle_rad = aa.angle();
    turn.axis = aa.axis();
    turns.push_back(turn);
  }
  return turns;
}

}  // namespace mpcal
