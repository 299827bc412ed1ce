/// \file simulate.h
/// \brief Synthetic hand-held sessions with known truth, for tests, the demo,
/// the benchmarks and the Cramér-Rao Monte Carlo. Presets follow the paper's
/// devices (docs/method.md §6).
///
/// Conventions:
/// - Sensor frame: the orthogonal frame of the error model (model.h): x along
///   the sensor's x axis, y in the plane of the x and y axes.
/// - A *direction* is the unit vector of the specific force at rest in the
///   sensor frame, i.e. "up" as the accelerometer sees it (the reaction to
///   gravity). A device lying flat, z axis up, has direction (0, 0, 1) and an
///   ideal sensor reads (0, 0, g) m/s² there.
/// - Specific force at rest = gravity_mps2 × direction. The reading in m/s² is
///   `truth.model.Forward(specific force)` + white noise, then quantised and
///   clipped, then converted to the output units.
/// - Noise: white, Gaussian, independent per axis and sample. The noise
///   density ND (m/s²/√Hz) is the square root of the one-sided power spectral
///   density, the figure datasheets quote; a sampled white noise fills the
///   band up to Nyquist, so the per-sample standard deviation is
///       σ = ND · √(rate_hz / 2).
///   SimulatedSession::noise_std_mps2 gives σ, for the Cramér-Rao bound.
/// - Random numbers come from std::mt19937_64 seeded from `seed`; normal and
///   uniform deviates are made by hand from its output (Box-Muller), so a seed
///   gives the same session with any standard library.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include "mpcal/calibration.h"
#include "mpcal/model.h"
#include "mpcal/recording.h"

namespace mpcal {

/// A device: its true errors and its noise. Every figure of the presets has
/// its source in a comment in src/simulate/presets.cc.
struct DevicePreset {
  std::string name;
  /// The device's errors at one power-up (the paper's trial 1).
  ErrorModel truth;
  /// White-noise density of each axis (m/s²/√Hz, one-sided; see above).
  double noise_density_mps2_per_sqrt_hz = 0.0;
  /// Output data rate (Hz).
  double rate_hz = 100.0;
  /// Measurement range (± m/s²); readings beyond it are clipped. 0 = unlimited.
  double range_mps2 = 0.0;
  /// Quantisation step (m/s², one LSB); 0 = none (floating-point output).
  double resolution_mps2 = 0.0;
  /// Spread of the bias from one power-up to the next (1σ, m/s² per axis).
  Eigen::Vector3d turn_on_bias_std_mps2 = Eigen::Vector3d::Zero();
  /// The gyroscope's errors (gyro_calibration.h): the true rate is
  /// ω = gyro_m (reading − bias), so a reading is gyro_m⁻¹ ω + bias + noise.
  /// gyro_m holds the scale factors on its diagonal and the misalignments
  /// (rad) off it.
  Eigen::Matrix3d gyro_m = Eigen::Matrix3d::Identity();
  Eigen::Vector3d gyro_bias_radps = Eigen::Vector3d::Zero();
  /// White-noise density of the gyroscope (rad/s/√Hz, one-sided), and the
  /// random walk of its bias (rad/s/√s, the rate random walk K).
  double gyro_noise_density_radps_per_sqrt_hz = 1e-3;
  double gyro_bias_walk_radps_per_sqrt_s = 0.0;
};

/// The preset called `name`: "colibri", "inertiacube3" or "mti-g"
/// (case-insensitive).
/// \throws mpcal::Error for an unknown name (the message lists the known).
DevicePreset FindPreset(const std::string& name);
/// The names FindPreset knows, in the paper's order.
std::vector<std::string> PresetNames();

/// The 26 cube directions of Syed et al. (2007), unit vectors of the gravity
/// reaction in the sensor frame: the 6 faces (+x, −x, +y, −y, +z, −z), then
/// the 12 edges, then the 8 corners. The first six alone are the classical
/// six-position calibration.
std::vector<Eigen::Vector3d> CubeDirections26();

struct SimulateStaticOptions {
  /// The device simulated (errors, noise, rate, range, resolution).
  DevicePreset device;
  /// Seeds every random draw; the same options and seed give the same session.
  std::uint64_t seed = 1;
  /// Number of positions: up to 26, the first `positions` cube directions
  /// (faces first); beyond 26, the 26 plus directions drawn uniformly on the
  /// sphere. Each cube direction is tilted by an angle uniform in
  /// [0, tilt_deg] about a random axis, as a hand holds it.
  int positions = 26;
  /// Largest tilt of a cube position from its nominal direction (degrees).
  double tilt_deg = 5.0;
  /// Still time per position (s). The paper held each for 40-60 s.
  double dwell_s = 10.0;
  /// Duration of each hand turn between positions (s), including the rest
  /// before the first position.
  double turn_s = 2.0;
  /// Rest at the start, before the first turn (s); device lying roughly flat.
  /// Not one of the positions (not in still_ranges). 0 = none.
  double initial_rest_s = 10.0;
  /// Sample rate (Hz); 0 = the device's rate.
  double rate_hz = 0.0;
  /// Hand shake during turns: RMS of the random linear acceleration per axis
  /// (m/s²) and of the small fast rotations (degrees). Both fade to zero at
  /// the ends of a turn; still parts have only sensor noise.
  double shake_accel_mps2 = 1.5;
  double shake_rotation_deg = 3.0;
  /// Also simulate gyroscope readings: the true angular rate through the
  /// device's gyroscope errors (device.gyro_m, device.gyro_bias_radps, its
  /// random walk) plus white noise of this density (rad/s/√Hz; negative:
  /// the device's). Off by default.
  bool gyro = false;
  double gyro_noise_density_radps_per_sqrt_hz = -1.0;
  /// Add the Earth's rotation (7.292115e-5 rad/s) at this latitude to the
  /// true rate; nullopt: none.
  std::optional<double> earth_rate_latitude_deg;
  /// Units of the gyroscope columns: rad/s, or counts, an ADC reading
  /// round(gyro_counts_offset + reading_radps × gyro_counts_per_radps).
  GyroUnits gyro_units = GyroUnits::kRadps;
  double gyro_counts_offset = 32768.0;
  double gyro_counts_per_radps = 4780.0;
  /// A bias drifting linearly over the session (m/s² per s, per axis): the
  /// device's bias is reached at the last sample, as a calibration file
  /// states a drifting bias (calibration.h, BiasDrift).
  Eigen::Vector3d bias_drift_mps2_per_s = Eigen::Vector3d::Zero();
  /// Units written: m/s²; g (readings divided by 9.80665); or counts, an ADC
  /// reading round(counts_offset + reading_mps2 × counts_per_mps2).
  AccelUnits units = AccelUnits::kMps2;
  double counts_offset = 32768.0;
  double counts_per_mps2 = 400.0;

  /// "" when valid, otherwise a message naming the first bad field.
  std::string Validate() const;
};

struct SimulatedSession {
  /// The readings (units as asked), time from 0 s, source "<simulated>".
  Recording recording;
  /// The truth as a calibration file would hold it: model, gravity, input
  /// units and mps2_per_unit, such that truth.Correct(reading) is the true
  /// specific force (m/s²) up to noise. For counts, mps2_per_unit =
  /// 1/counts_per_mps2 and truth.model.bias_mps2 includes the ADC offset
  /// (counts_offset / counts_per_mps2 on each axis).
  Calibration truth;
  /// Sample ranges [begin, end) of the still part of each position, and its
  /// true direction, in order (the initial rest is not a position here).
  std::vector<std::pair<std::size_t, std::size_t>> still_ranges;
  std::vector<Eigen::Vector3d> directions;
  /// Per-sample white-noise σ of each axis (m/s², i.e. on reading ×
  /// mps2_per_unit): ND · √(rate/2).
  Eigen::Vector3d noise_std_mps2 = Eigen::Vector3d::Zero();
  /// Quantisation step of the readings in m/s² (the device resolution, or one
  /// count, whichever is coarser); 0 = none. Adds up to step²/12 of variance.
  double quantisation_step_mps2 = 0.0;
  /// The sample rate used (Hz).
  double rate_hz = 0.0;
  /// With the gyroscope: its per-sample white-noise σ (rad/s, on reading ×
  /// radps_per_unit) and the true angular rate at every sample (rad/s, body
  /// frame), which truth.gyroscope's Correct returns up to the noise and the
  /// bias walk (truth.gyroscope's bias is the one at time 0).
  double gyro_noise_std_radps = 0.0;
  std::vector<Eigen::Vector3d> true_rate_radps;
};

/// Simulates one hand-held static session: initial rest, then for each
/// position a hand turn (a smooth minimum-jerk rotation from the previous
/// orientation plus shake) and a still dwell.
/// \param gravity_mps2 local gravity magnitude (m/s²), also stored in truth.
/// \throws mpcal::Error for invalid options (message from Validate()) or a
///   gravity that is not positive and finite.
SimulatedSession SimulateStatic(const SimulateStaticOptions& options,
                                double gravity_mps2 = kStandardGravityMps2);

/// The seed of trial `trial` (1-based) of SimulateTrials, derived from
/// `base_seed` by SplitMix64 so that trials are independent.
std::uint64_t TrialSeed(std::uint64_t base_seed, int trial);

/// The options of each of `trials` power-ups of one device (see
/// SimulateTrials), so that a caller can simulate and write them one at a
/// time: trial i (1-based) is element i−1.
/// \throws mpcal::Error for invalid options or trials < 1.
std::vector<SimulateStaticOptions> TrialOptions(const SimulateStaticOptions& options,
                                                int trials);

/// `trials` sessions of one device, as the paper's repeated calibrations
/// (docs/method.md §4): scale-factor errors and non-orthogonality are those of
/// options.device.truth in every trial; the bias is redrawn at each power-up
/// as device.truth.bias_mps2 + N(0, diag(device.turn_on_bias_std_mps2²)).
/// Trial i uses seed TrialSeed(options.seed, i) (positions, tilts, shake and
/// noise differ); the bias draws come from their own stream of options.seed.
/// Equivalent to SimulateStatic over TrialOptions(options, trials).
/// \throws mpcal::Error as SimulateStatic, or for trials < 1.
std::vector<SimulatedSession> SimulateTrials(const SimulateStaticOptions& options,
                                             int trials,
                                             double gravity_mps2 = kStandardGravityMps2);

}  // namespace mpcal
