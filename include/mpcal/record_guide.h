/// \file record_guide.h
/// \brief Guidance while a session is recorded: where gravity points now,
/// how still the sensor is, which positions are held, which one to hold
/// next, and when the positions so far are enough (docs/method.md §3.11).
///
/// SessionGuide is fed the rows as they arrive (time in s, accelerometer in
/// m/s², gyroscope in rad/s when there is one), split in any way, and
/// returns facts: the command words them.
///
/// - Stillness is static detection's rule (detect.h), judged as the rows
///   arrive by StillnessMonitor's rule (still_windows.h): the statistic of every window
///   against the threshold of the statistics so far (refreshed every `window_s` of the
///   log's clock), runs of still windows trimmed by `settle_s` at both ends, a run
///   continued across a bump as DetectStatic merges it. A position is captured when its
///   trimmed run reaches `min_static_s`; it goes on collecting samples while it is held.
/// - The 26 cube directions are coverage.h's (CanonicalDirections()); one
///   is held when a captured position lies within `near_deg` of it.
/// - The bound is the Cramér-Rao bound (cramer_rao.h) of the captured
///   positions: their measured directions, their samples, and the noise
///   pooled over them (per axis), for an ideal sensor of the chosen model.
/// - The target 1σ of each parameter group (biases, scale-factor errors,
///   angles), unless given: `target_factor` (1.5) times the largest bound in
///   that group of the 26 cube directions, each held with the median samples
///   of the captured positions, at the pooled noise. So the session is done
///   when its positions determine every parameter within 1.5 times what the
///   full 26-position cube would with the same holds.
/// - The next target is the direction not yet held that, added with the
///   median samples, gives the smallest worst ratio of bound to target over
///   the parameters. While the positions cannot determine the parameters
///   even with one more, it is the direction not yet held farthest from
///   every held one (the first in the cube's order among equals).
/// - With a gyroscope, each turn between two captured positions is
///   integrated (gyro.h's IntegrateRotation, the bias measured at the
///   position before): a body axis is turned about once the components of
///   the turns' rotation vectors about it reach `min_turn_deg` in root sum
///   of squares: a column of the gyroscope's M is only seen through turns
///   about its axis (docs/method.md §7).
#pragma once

#include <array>
#include <cstddef>
#include <limits>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mpcal/detect.h"
#include "mpcal/model.h"
#include "mpcal/units.h"

namespace mpcal {

/// The parameter groups a target 1σ is given for.
enum class ParameterGroup { kBias, kScale, kAngle };
/// The group of packed parameter `index` (order of kParameterNames).
ParameterGroup GroupOf(int index);

struct GuideOptions {
  /// The still rule and the minimum hold (min_static_s).
  DetectOptions detect;
  /// The model the session is meant to calibrate.
  ModelKind model = ModelKind::kShinElSheimy9;
  /// Target 1σ of every bias (m/s²), scale-factor error (dimensionless) and
  /// angle (rad); 0 = the default rule (see the file's comment).
  double target_bias_mps2 = 0.0;
  double target_scale = 0.0;
  double target_angle_rad = 0.0;
  /// The default rule's factor on the full cube's bound.
  double target_factor = 1.5;
  /// A cube direction is held when a position is within this (deg).
  double near_deg = 25.0;
  /// Gravity (m/s²) of the bound.
  double gravity_mps2 = kStandardGravityMps2;
  /// Rotation about a body axis (deg) that counts as turned about it.
  double min_turn_deg = 45.0;

  /// Empty string when valid, otherwise names the first bad field.
  std::string Validate() const;
};

/// Where gravity points now (the mean reading over the last window).
struct GravityNow {
  bool known = false;
  /// Unit vector of the mean reading (the gravity reaction, as coverage.h).
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();
  /// Index into CanonicalDirections() of the nearest, and the angle to it.
  int nearest = 0;
  double off_deg = 0.0;
};

/// How still the sensor is now.
struct StillMeter {
  /// False until the first window is judged.
  bool known = false;
  /// The motion statistic of the latest window and the threshold (m/s²).
  double statistic_mps2 = 0.0;
  double threshold_mps2 = 0.0;
  bool still = false;
  /// How long the current still run has been held (s, from its first still
  /// window, settling included), and its progress to the minimum hold (0-1;
  /// 1 once captured).
  double held_s = 0.0;
  double progress = 0.0;
};

/// A captured position.
struct GuidePosition {
  /// Its kept samples (settling trimmed): first and last time (log clock).
  double start_s = 0.0;
  double end_s = 0.0;
  /// Mean and per-axis standard deviation of the readings (m/s²), and the
  /// samples behind them.
  Eigen::Vector3d mean_mps2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d std_mps2 = Eigen::Vector3d::Zero();
  std::size_t samples = 0;
  /// Mean gyroscope reading (rad/s; zero without a gyroscope).
  Eigen::Vector3d gyro_mean_radps = Eigen::Vector3d::Zero();
  /// Nearest cube direction (index into CanonicalDirections()), the angle
  /// to it (deg) and whether it is within near_deg.
  int nearest = 0;
  double off_deg = 0.0;
  bool holds_nearest = false;
};

/// The bound of the captured positions against the targets.
struct GuideBound {
  /// False while the positions do not determine the parameters.
  bool determined = false;
  /// 1σ bound of each packed parameter (order of kParameterNames; NaN when
  /// not determined; the angles 0 for the 6-parameter model).
  std::array<double, kNumModelParameters> std{};
  /// Target 1σ of each group (bias, scale, angle).
  std::array<double, 3> target{};
  /// The parameter with the largest bound over its target, and that ratio
  /// (infinite when not determined).
  int worst = 0;
  double worst_ratio = std::numeric_limits<double>::infinity();
  /// Every parameter within its target.
  bool met() const { return determined && worst_ratio <= 1.0; }
};

/// The gyroscope's turns so far.
struct GuideTurns {
  bool gyro = false;
  int turns = 0;
  /// Root sum of squares of the turns' rotation about each body axis (deg),
  /// and whether it reaches min_turn_deg.
  std::array<double, 3> about_deg{};
  std::array<bool, 3> excited{};
  bool all_excited() const { return excited[0] && excited[1] && excited[2]; }
};

enum class GuideEventKind {
  kCaptured,    ///< a position reached the minimum hold
  kNextTarget,  ///< the direction to hold next
  kTurnNeeded,  ///< a body axis no turn has been about yet
  kDone,        ///< every parameter within its target (and every axis turned)
};

struct GuideEvent {
  GuideEventKind kind = GuideEventKind::kCaptured;
  /// Log time of the window that decided it.
  double time_s = 0.0;
  /// kCaptured: positions captured so far, and the position's nearest cube
  /// direction (index into CanonicalDirections()) and angle to it (deg).
  int positions = 0;
  int direction = 0;
  double off_deg = 0.0;
  /// kNextTarget: the cube direction to hold next.
  int target = -1;
  /// kTurnNeeded: the body axis (0 x, 1 y, 2 z).
  int axis = 0;
  /// The bound when the event was decided.
  GuideBound bound;
};

/// Guides a session as its rows arrive. Memory: a window of rows, the
/// captured positions, and the gyroscope's rows since the last position.
class SessionGuide {
 public:
  /// \throws mpcal::Error if the options are invalid.
  explicit SessionGuide(const GuideOptions& options);
  ~SessionGuide();
  SessionGuide(SessionGuide&&) noexcept;
  SessionGuide& operator=(SessionGuide&&) noexcept;
  SessionGuide(const SessionGuide&) = delete;
  SessionGuide& operator=(const SessionGuide&) = delete;

  /// Rows in time order (time strictly increasing across calls); `gyro_radps`
  /// empty, or as long as the others in every call. Returns the events they
  /// decided, in order.
  /// \throws mpcal::Error if the lengths differ, time does not increase, a
  ///   value is not finite, or the window is shorter than two samples.
  std::vector<GuideEvent> Feed(std::span<const double> time_s,
                               std::span<const Eigen::Vector3d> accel_mps2,
                               std::span<const Eigen::Vector3d> gyro_radps = {});

  GravityNow Gravity() const;
  StillMeter Meter() const;
  const std::vector<GuidePosition>& Positions() const;
  /// Per cube direction (order of CanonicalDirections()): held or not.
  std::vector<bool> Held() const;
  /// The direction to hold next (-1 when done or none is left).
  int NextTarget() const;
  GuideBound Bound() const;
  GuideTurns Turns() const;
  /// The bound met and, with a gyroscope, every axis turned about.
  bool Done() const;

 private:
  struct State;
  std::unique_ptr<State> state_;
};

/// The bound (as GuideBound) of `positions` at the given targets; `noise` is
/// the per-sample 1σ of each axis (m/s²). For the tests and the guide.
GuideBound BoundOf(std::span<const GuidePosition> positions,
                   const Eigen::Vector3d& noise_std_mps2,
                   const std::array<double, 3>& target,
                   const GuideOptions& options);

}  // namespace mpcal
