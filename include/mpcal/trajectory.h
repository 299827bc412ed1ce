/// \file trajectory.h
/// \brief Strapdown integration of accelerometer readings to a trajectory, as
/// the paper's field verification does it (docs/method.md §5): attitude at the
/// start by levelling at the initial rest or from a stated mount, propagated
/// by the gyroscope when the log has one; gravity of the local magnitude
/// removed; trapezoidal double integration; velocity reset to zero at the
/// detected stops (zero-velocity updates). Plus the still test it uses, and
/// the horizontal error metrics against a reference track.
///
/// Frames: the sensor frame s is the accelerometer's (after correction, the
/// orthogonal frame of model.h). The navigation frame n is local level, z up;
/// its heading is arbitrary (x is wherever the initial attitude puts it) until
/// AlignToReference rotates the path about z. Positions in metres, times in
/// seconds on the clock of the input.
#pragma once

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace mpcal {

/// How the initial attitude is found.
enum class MountMode {
  /// Levelling: the mean specific force over the initial rest is taken as
  /// "up". Absorbs the horizontal part of a constant accelerometer bias into a
  /// tilt, exactly, as long as the sensor does not rotate.
  kLevel,
  /// The sensor's z axis points up (a pole held upright, the paper's
  /// setting): no levelling, so the whole bias shows in the trajectory.
  kZUp,
};
/// "level" or "z-up".
std::string_view ToString(MountMode mode);
/// Inverse of ToString; nullopt if unknown.
std::optional<MountMode> ParseMountMode(std::string_view name);

struct StillOptions {
  /// Length of the centred moving window of the motion statistics (s).
  double window_s = 0.5;
  /// A sample is still when the moving standard deviation of the
  /// accelerometer (norm over the axes) is below threshold_factor × its quiet
  /// level, and, when there is a gyroscope, the same holds for the
  /// gyroscope's statistic: the RMS over the window of its difference from
  /// its median reading (so that a steady turn is not still). The quiet level
  /// is the 10th percentile of the statistic over the log. Note that walking
  /// at a perfectly steady speed would look still to an accelerometer; real
  /// steps never are.
  double threshold_factor = 4.0;
  /// Floors of the thresholds (m/s², rad/s), for noise-free data.
  double min_accel_threshold_mps2 = 0.005;
  double min_gyro_threshold_radps = 0.002;
  /// Still stretches shorter than this (s) are treated as motion.
  double min_still_s = 0.3;

  /// "" when valid, otherwise names the first bad field.
  std::string Validate() const;
};

struct StillResult {
  /// One flag per sample.
  std::vector<bool> still;
  /// Still stretches [begin, end) in sample indices, in order.
  std::vector<std::pair<std::size_t, std::size_t>> intervals;
  /// Samples [0, initial_rest_end) are the initial rest (0 when the log does
  /// not start still).
  std::size_t initial_rest_end = 0;
  double accel_threshold_mps2 = 0.0;
  double gyro_threshold_radps = 0.0;  ///< 0 without a gyroscope
  /// The accelerometer's motion statistic per sample (m/s²).
  std::vector<double> accel_std_mps2;
};

/// Marks still samples of a log.
/// \param time_s strictly increasing sample times (s)
/// \param specific_force_mps2 accelerometer readings (m/s², any scale close
///   to right: only their variation matters)
/// \param gyro_radps gyroscope readings (rad/s), same length, or empty
/// \throws mpcal::Error for invalid options, mismatched lengths or fewer
///   samples than one window.
StillResult DetectStill(std::span<const double> time_s,
                        std::span<const Eigen::Vector3d> specific_force_mps2,
                        std::span<const Eigen::Vector3d> gyro_radps,
                        const StillOptions& options);

struct IntegrateOptions {
  /// Magnitude of gravity removed from the vertical (m/s²); use the local
  /// value (a wrong one only affects the vertical channel).
  double gravity_mps2 = 9.80665;
  /// Attitude at the start: levelling at the initial rest, or z up.
  MountMode mount = MountMode::kLevel;
  /// Propagate the attitude with the gyroscope when there is one. Its bias
  /// is the mean over the initial rest.
  bool use_gyro = true;
  /// Reset the velocity to zero at still samples.
  bool zero_velocity_updates = true;
  /// Shortest initial rest accepted (s) for levelling or the gyroscope bias.
  double min_initial_rest_s = 1.0;

  /// "" when valid, otherwise names the first bad field.
  std::string Validate() const;
};

/// A path: times and positions (m), one per sample.
struct TimedPath {
  std::vector<double> time_s;
  std::vector<Eigen::Vector3d> position_m;
  std::size_t size() const { return time_s.size(); }
  bool empty() const { return time_s.empty(); }
  /// Position at `t` by linear interpolation; clamped at the ends.
  /// \throws mpcal::Error (kInput) for an empty path, or times and positions
  ///   of different lengths.
  Eigen::Vector3d At(double t) const;
};

struct IntegrationResult {
  /// Positions in the navigation frame from the first sample (at the origin).
  TimedPath path;
  /// Velocity (m/s) per sample.
  std::vector<Eigen::Vector3d> velocity_mps;
  /// Initial attitude (maps sensor to navigation frame).
  Eigen::Matrix3d R_nav_sensor = Eigen::Matrix3d::Identity();
  /// Whether the gyroscope propagated the attitude, and its bias (rad/s).
  bool gyro_used = false;
  Eigen::Vector3d gyro_bias_radps = Eigen::Vector3d::Zero();
  /// Tilt of the initial attitude from z-up (rad).
  double initial_tilt_rad = 0.0;
  /// Samples where the velocity was reset.
  std::size_t zero_velocity_samples = 0;
};

/// Integrates specific force to a path.
/// \param still as DetectStill gives it for the same samples
/// \throws mpcal::Error for invalid options, mismatched lengths, or when
///   levelling (or the gyroscope bias) needs an initial rest shorter than
///   options.min_initial_rest_s.
IntegrationResult IntegrateTrajectory(
    std::span<const double> time_s,
    std::span<const Eigen::Vector3d> specific_force_mps2,
    std::span<const Eigen::Vector3d> gyro_radps,
    const StillResult& still,
    const IntegrateOptions& options);

/// Places `path` so that it starts at `reference` at time `t_start`, and
/// rotates it about the vertical so that its heading from `t_start` to
/// `t_heading` matches the reference's: the paper's alignment of the first
/// point and the initial heading. Returns the rotation angle (rad, about up).
double AlignToReference(TimedPath& path,
                        const TimedPath& reference,
                        double t_start,
                        double t_heading);

/// Figures of a path compared with the reference at the reference's epochs.
struct PathMetrics {
  /// Horizontal distance between the first and last point (m): zero for a
  /// perfect sensor on a closed loop (the paper's Table 7).
  double start_end_distance_m = 0.0;
  /// RMS and maximum horizontal distance to the reference (m).
  double horizontal_rms_m = 0.0;
  double horizontal_max_m = 0.0;
  /// Horizontal length of the path (m).
  double path_length_m = 0.0;
};

/// Horizontal length (m) of the polyline through the points of `path` that
/// are at least `step_m` apart (so that centimetre jitter at rest does not
/// add up): the jitter-robust length of a GNSS or integrated track.
/// \throws mpcal::Error (kOption) for a negative or non-finite step.
double HorizontalPathLength(std::span<const Eigen::Vector3d> positions_m, double step_m);

/// Metrics of `path` sampled at the reference epochs `reference`.
PathMetrics ComparePaths(const TimedPath& path,
                         const TimedPath& reference,
                         double step_m);

}  // namespace mpcal
