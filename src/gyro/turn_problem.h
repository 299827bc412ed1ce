// The data of the gyroscope problem, from a recording, its static positions
// and the accelerometer's calibration: per position the gravity direction
// and the gyroscope's mean (the bias) and scatter; per turn the bias-free
// angle increments and the variance of its residual.
#pragma once

#include <array>
#include <cstddef>
#include <span>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "mpcal/calibration.h"
#include "mpcal/detect.h"
#include "mpcal/gyro.h"
#include "mpcal/gyro_calibration.h"
#include "mpcal/recording.h"
#include "mpcal/recording_view.h"
#include "rotation.h"

namespace mpcal::internal {

/// rad/s per unit of the readings `recording` holds, for a calibration
/// `gyro` of its gyroscope: the calibration's nominal scale for raw counts,
/// 1 otherwise (a log in deg/s is held in rad/s, whatever units the
/// calibration was recorded in).
inline double HeldRadpsPerUnit(const RecordingView& recording,
                               const GyroCalibration& gyro) {
  if (recording.gyro_units != GyroUnits::kCounts) return 1.0;
  return gyro.radps_per_unit > 0.0 ? gyro.radps_per_unit : 1.0;
}

/// The last evaluations of one turn at an effective matrix M: its rotation
/// and the right perturbation per entry of M (3 × 9), or along one direction
/// of M (3 × 1). The solver asks for the residual at a candidate M and, once
/// it accepts the step, for the Jacobian at the same M; the evaluations
/// before and after the solve ask at its first and last point. Two entries,
/// so that a rejected candidate does not push out the accepted point.
struct TurnCache {
  struct Full {
    Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
    Eigen::Matrix<double, 3, 9> d_theta = Eigen::Matrix<double, 3, 9>::Zero();
    bool valid = false;
  };
  struct Along {
    Eigen::Matrix3d m = Eigen::Matrix3d::Zero();
    Eigen::Matrix3d direction = Eigen::Matrix3d::Zero();
    Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
    Eigen::Vector3d d_theta = Eigen::Vector3d::Zero();
    bool valid = false;
  };
  std::array<Full, 2> full;
  std::array<Along, 2> along;
  std::size_t next_full = 0;  // the least recently used entry
  std::size_t next_along = 0;
};

/// A gravity direction at a position's edge (unit, body frame at the edge):
/// the mean over the direction window with each sample carried to the edge
/// by the gyroscope at the nominal scale, the plain mean, and the window's
/// length. Equal, with no window, for a whole position's mean.
struct EdgeDirections {
  Eigen::Vector3d carried = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d still = Eigen::Vector3d::UnitZ();
  double window_s = 0.0;
};

struct TurnData {
  std::size_t from_position = 0;
  std::size_t begin = 0;  // first and last sample integrated (inclusive)
  std::size_t end = 0;
  double start_s = 0.0;
  double end_s = 0.0;
  /// Each sample interval: the bias-free readings at its two ends times its
  /// length (raw units × s).
  std::vector<TurnStep> steps;
  /// Both measures of the directions at the two edges (turn_weights.h
  /// chooses which the fit uses).
  EdgeDirections from;
  EdgeDirections to;
  /// Unit gravity directions (body frame) before and after, and an
  /// orthonormal basis of the plane perpendicular to the one after: the
  /// carried ones until UseDirections sets others.
  Eigen::Vector3d u_from = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d u_to = Eigen::Vector3d::UnitZ();
  Eigen::Matrix<double, 3, 2> basis_to = Eigen::Matrix<double, 3, 2>::Zero();
  /// Variance of each residual component (rad²): the two directions' part,
  /// and the gyroscope's part (white noise integrated over the turn plus the
  /// interpolated bias) in raw units² × s², to be multiplied by the square of
  /// the nominal scale.
  double direction_variance_rad2 = 0.0;
  double gyro_variance_raw2s2 = 0.0;
  /// Filled by TurnResidual and TurnResidualAlong, keyed by M alone: the
  /// steps must not change once the turn has been evaluated. A turn is
  /// evaluated by one thread at a time (Ceres gives each residual block to
  /// one thread).
  mutable TurnCache cache;

  double Sigma(double radps_per_unit) const;
};

struct TurnProblem {
  std::vector<TurnData> turns;
  /// Mean gyroscope reading at each position (raw units) and its centre.
  std::vector<GyroBiasSample> bias_raw;
  /// Typical per-sample white noise of the gyroscope at rest (raw units),
  /// and the median sample period (s).
  double noise_std_raw = 0.0;
  double sample_period_s = 0.0;
  /// Gyroscope samples in each position's mean (its own samples when it was
  /// recorded apart, Recording::gyro_samples).
  std::vector<std::size_t> bias_samples;
  /// g-sensitivity of the bias (raw units per m/s²); zero when not estimated.
  Eigen::Matrix3d g_sensitivity_raw_per_mps2 = Eigen::Matrix3d::Zero();
  bool g_sensitivity_used = false;
  /// F statistic of the regression of the biases on f (0: not computed).
  double g_sensitivity_f = 0.0;
  /// Mean over the positions of bias − G f (raw units).
  Eigen::Vector3d bias_without_g_raw = Eigen::Vector3d::Zero();
};

/// The gyroscope's samples as measured: its own stream when it was recorded
/// apart (Recording::gyro_samples; the rows then hold means over each row,
/// which neighbouring rows share, so that their scatter is not the sensor's
/// noise), else the rows'.
struct GyroSamples {
  std::span<const double> time_s;
  std::span<const Eigen::Vector3d> rate;
};
GyroSamples SamplesOf(const RecordingView& recording);
/// Samples [first, last) whose times lie within [from_s, to_s].
std::pair<std::size_t, std::size_t> SamplesWithin(const GyroSamples& samples,
                                                  double from_s,
                                                  double to_s);

/// \throws mpcal::Error when the recording has no gyroscope, fewer than two
///   positions are given, or a position lies outside the recording.
/// `direction_window_s` and `g_sensitivity` as in GyroOptions.
/// `carry_radps_per_unit` > 0: the specific force of each sample of a
/// direction window is carried by the gyroscope (at this nominal scale) to
/// the window's edge, so that the hand's sway within it does not count.
TurnProblem BuildTurnProblem(const RecordingView& recording,
                             std::span<const StaticInterval> intervals,
                             const Calibration& accel,
                             double direction_window_s,
                             GSensitivity g_sensitivity,
                             double min_f,
                             double carry_radps_per_unit);

/// Sets the turn's directions (and the basis at `u_to`); forgets its cache.
void UseDirections(const Eigen::Vector3d& u_from,
                   const Eigen::Vector3d& u_to,
                   TurnData* turn);

/// Residual of one turn (unwhitened, rad: the tilt components in the basis
/// at u_to) at the effective matrix `m` applied to raw increments, and its
/// 2 × 9 Jacobian when asked. Returns the rotation over the turn. The
/// Jacobian is computed even when not asked (it costs little more than the
/// rotation, which needs every sample's exponential) and kept in the turn's
/// cache with the rotation: a second call at the same `m` reads them.
Eigen::Matrix3d TurnResidual(const TurnData& turn,
                             const Eigen::Matrix3d& m,
                             Eigen::Vector2d* residual,
                             Eigen::Matrix<double, 2, 9>* jacobian);

/// The same residual and, when `derivative` is not null, its derivative
/// along one direction of M (δM = `direction`): for a fit of a common scale.
/// Cached as TurnResidual's.
Eigen::Matrix3d TurnResidualAlong(const TurnData& turn,
                                  const Eigen::Matrix3d& m,
                                  const Eigen::Matrix3d& direction,
                                  Eigen::Vector2d* residual,
                                  Eigen::Vector2d* derivative);

/// Angle (rad) between the carried direction Rᵀ u_from and u_to.
double TurnTilt(const TurnData& turn, const Eigen::Matrix3d& rotation);

}  // namespace mpcal::internal
