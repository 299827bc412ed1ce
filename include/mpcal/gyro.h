/// \file gyro.h
/// \brief The gyroscope from the same hand-held session (Tedaldi, Pretto &
/// Menegatti, ICRA 2014; docs/method.md §7): between two static positions the
/// sensor turns, and the gyroscope integrated along the turn must carry the
/// gravity direction measured at the first position onto the one measured
/// at the next.
///
/// - Turns: the stretches between consecutive static positions of the
///   detection, integrated from the last sample of position k to the first
///   of position k+1, where the gyroscope and the accelerometer show the
///   sensor at rest up to the motion (detection trims about 0.8 s of each
///   position's ends for the accelerometer's mean; a turn integrated over
///   that still time would only gather noise).
/// - Bias: the mean reading at every static position (bias plus the Earth
///   rate projected on the body there), interpolated linearly in time
///   between the centres of the positions, so that a bias that drifts
///   during the session does not leak into M.
/// - Integration: the exact exponential map, R = Π exp([M w_i]×), with w_i
///   the bias-free rate integrated over each sample interval by the cubic
///   through the four readings around it (the recorded sample times, not a
///   nominal rate), with the two-sample coning term.
/// - Residual: with u_k the unit specific force at position k (body frame =
///   the accelerometer's orthogonal frame, by its calibration), the
///   predicted direction after the turn is Rᵀ u_k; the residual is its tilt
///   from the measured u_{k+1}, two components in the plane perpendicular to
///   u_{k+1} (a rotation about gravity is invisible).
/// - Weights: per turn, the noise of both measured directions (accelerometer
///   noise of the means over g, and the hand's sway or the gyroscope's
///   noise over the direction windows, see GyroDirections), the integrated
///   gyroscope white noise (σ·√(period·duration), σ from the positions'
///   second differences), the uncertainty of the interpolated bias and the
///   bias's random walk across the turn; the covariance is scaled up by the
///   variance factor as the accelerometer's is ((10 + χ²)/(10 + dof)).
#pragma once

#include <array>
#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "mpcal/calibration.h"
#include "mpcal/detect.h"
#include "mpcal/gyro_calibration.h"
#include "mpcal/recording.h"
#include "mpcal/recording_view.h"

namespace mpcal {

/// The 9 entries of M, row-major: "m_xx", "m_xy", …, "m_zz" (row = output
/// axis, column = input axis).
inline constexpr std::array<std::string_view, 9> kGyroParameterNames = {
    "m_xx", "m_xy", "m_xz", "m_yx", "m_yy", "m_yz", "m_zx", "m_zy", "m_zz"};

/// Whether the bias's g-sensitivity is modelled (GyroOptions::g_sensitivity).
enum class GSensitivity {
  kOff,   ///< never
  kAuto,  ///< when the positions' biases show it (F test, see below)
  kOn,    ///< always (15 positions or more)
};
std::string_view ToString(GSensitivity mode);

struct GyroOptions {
  /// Nominal rad/s per unit of the readings. 0: from the recording's units
  /// (rad/s), or for raw counts found from the turns (a least-squares fit of
  /// one common scale before the full M). Give it when known.
  double radps_per_unit = 0.0;
  /// The gravity directions at the two ends of a turn are the accelerometer's
  /// mean over this long (s) at the end of the position before and at the
  /// start of the one after: the hand drifts during a position, and the
  /// gyroscope starts integrating where the position ends. 0 = the mean of
  /// the whole position.
  double direction_window_s = 1.0;
  /// Model the bias's g-sensitivity, b = b₀ + G f (docs/method.md §7): G is
  /// regressed from the positions' biases on their specific force (and
  /// time), and G f follows the specific force through each turn; the rest
  /// of the bias is interpolated in time. Needs 15 positions or more. kAuto
  /// keeps it when the regression on f explains the biases beyond chance
  /// (F statistic above g_sensitivity_min_f: 5 is beyond the 0.1 % point of
  /// F(9, 26)). On imu_tk's Xsens recording it takes the turn residual from
  /// 0.38° to 0.14°.
  GSensitivity g_sensitivity = GSensitivity::kAuto;
  double g_sensitivity_min_f = 5.0;
  /// Iteration cap of the Levenberg-Marquardt solver.
  int max_iterations = 100;
  /// An entry of M whose 1σ exceeds this (dimensionless; 0.005 = 0.5 % of
  /// scale or 5 mrad of misalignment) is reported as poorly determined.
  double poorly_determined_std = 0.005;

  /// Empty string when valid, otherwise names the first bad field.
  std::string Validate() const;
};

/// One turn between consecutive static positions.
struct GyroTurn {
  /// Static position before the turn (index into the detection's
  /// intervals); the one after is from_position + 1.
  std::size_t from_position = 0;
  /// Samples integrated: from `begin` (last sample of the position before)
  /// to `end` (first sample of the position after), inclusive.
  std::size_t begin = 0;
  std::size_t end = 0;
  double start_s = 0.0;
  double end_s = 0.0;
  /// Rotation over the turn with the calibrated gyroscope (nominal before
  /// calibration): angle (rad) and unit axis in the body frame at its start.
  double angle_rad = 0.0;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();
  /// Tilt between the carried and the measured gravity direction (rad),
  /// before and after calibration, and the 1σ of each of its two components.
  double residual_before_rad = 0.0;
  double residual_after_rad = 0.0;
  double sigma_rad = 0.0;

  double duration_s() const { return end_s - start_s; }
};

enum class GyroFindingKind {
  /// Turns too few for the 9 entries of M (each gives two equations).
  kTooFewTurns,
  /// The turns leave combinations of M undetermined (no turns about an
  /// axis): `parameters` and `turn_axes` say which and what to add.
  kUndetermined,
  /// Entries of M determined worse than GyroOptions::poorly_determined_std.
  kPoorlyDetermined,
};
std::string_view ToString(GyroFindingKind kind);

/// A fact about the session's turns, for apps/ to put in words.
struct GyroFinding {
  GyroFindingKind kind = GyroFindingKind::kUndetermined;
  /// Indices into kGyroParameterNames.
  std::vector<int> parameters;
  /// Body axes (x, y, z) about which turns would determine them.
  std::array<bool, 3> turn_axes = {false, false, false};
  /// kTooFewTurns: turns found and turns needed; kPoorlyDetermined: the
  /// largest 1σ and the threshold (GyroOptions::poorly_determined_std).
  double value = 0.0;
  double limit = 0.0;
};

enum class GyroStatus { kConverged, kNoConvergence, kUndetermined };
std::string_view ToString(GyroStatus status);

/// Which measure of the gravity directions at the turns' edges the fit
/// used, and why. The hand sways while it holds a position: the plain mean
/// of a direction window then errs by the sway's angle, while the mean with
/// each sample carried to the edge by the gyroscope errs by the gyroscope's
/// noise integrated over the window. The two measures' difference holds
/// both; the one expected to err less is used, and its error is in the
/// turns' weights.
struct GyroDirections {
  /// The carried mean (true) or the plain mean (false).
  bool carried = false;
  /// Per tangent component at one edge (rad, 1σ): the sway's error of the
  /// plain mean (estimated from the two measures' differences, 0 when they
  /// differ no more than the gyroscope's noise explains) and the carried
  /// mean's error from the gyroscope's noise (mean over the edges).
  double sway_rad = 0.0;
  double carry_noise_rad = 0.0;
};

struct GyroResult {
  GyroStatus status = GyroStatus::kUndetermined;
  /// The solver's own message (for kNoConvergence).
  std::string message;
  /// The model, its covariance, per-position bias and fit summary.
  GyroCalibration calibration;
  std::vector<GyroTurn> turns;
  std::vector<GyroFinding> findings;
  /// Whitened Fisher information JᵀWJ of the 9 entries of M at the estimate
  /// (no variance factor) and its singular values, largest first.
  Eigen::Matrix<double, 9, 9> information = Eigen::Matrix<double, 9, 9>::Zero();
  Eigen::Matrix<double, 9, 1> singular_values = Eigen::Matrix<double, 9, 1>::Zero();
  /// Factor applied to (JᵀWJ)⁻¹ for the covariance: max(1, (10 + χ²)/(10 + dof)).
  double covariance_scale = 1.0;
  /// F statistic of the positions' biases regressed on the specific force
  /// (0 when not computed); calibration.g_sensitivity_radps_per_mps2 is set
  /// when the model kept it.
  double g_sensitivity_f = 0.0;
  /// The directions' measure (see GyroDirections).
  GyroDirections directions;

  bool converged() const { return status == GyroStatus::kConverged; }
};

/// Calibrates the gyroscope of `recording` from the turns between the static
/// positions `intervals` (as DetectStatic found them, in time order), with
/// the gravity directions from the accelerometer's calibration `accel`.
/// A session whose turns do not determine M returns kUndetermined with its
/// findings (no exception: the accelerometer's calibration stands alone).
/// \throws mpcal::Error when the recording has no gyroscope readings, an
///   interval lies outside it, or the options are invalid.
GyroResult CalibrateGyroscope(const RecordingView& recording,
                              std::span<const StaticInterval> intervals,
                              const Calibration& accel,
                              const GyroOptions& options);

/// The Cramér-Rao bound of M (9×9 covariance, row-major) for this session:
/// the inverse of the Fisher information JᵀWJ at `truth` (its M, bias
/// ignored: the bias is measured at the positions as CalibrateGyroscope
/// does), with the same per-turn weights.
/// \throws mpcal::Error as CalibrateGyroscope, or when the turns do not
///   determine M.
Eigen::Matrix<double, 9, 9> GyroCramerRaoBound(const RecordingView& recording,
                                               std::span<const StaticInterval> intervals,
                                               const Calibration& accel,
                                               const GyroCalibration& truth);

/// The turns between the static positions `intervals` scored with a known
/// calibration `gyro` (as read from an IMU file; its nominal scale, bias at
/// every position and g-sensitivity as CalibrateGyroscope uses them): per
/// turn the tilt residual before (nominal scale, M = I) and after (M), its
/// 1σ, and the calibrated rotation's angle and axis. No solve.
/// \throws mpcal::Error as CalibrateGyroscope.
std::vector<GyroTurn> ScoreGyroTurns(const RecordingView& recording,
                                     std::span<const StaticInterval> intervals,
                                     const Calibration& accel,
                                     const GyroCalibration& gyro);

/// The rotation of the body over samples [begin, end] of `recording` with
/// the gyroscope model `gyro` (constant bias), by the exponential map:
/// R_begin_end, which maps vectors in the body frame at `end` to the body
/// frame at `begin` (so a fixed direction u seen at begin is Rᵀ u at end).
/// \throws mpcal::Error when the range is outside the recording or the
///   recording has no gyroscope.
Eigen::Matrix3d IntegrateRotation(const RecordingView& recording,
                                  std::size_t begin,
                                  std::size_t end,
                                  const GyroCalibration& gyro);

}  // namespace mpcal
