/// \file simulate_noise.h
/// \brief Still recordings with known noise terms, for tests, benchmarks and
/// for users to learn `mpcal noise` on.
///
/// Each axis of the accelerometer (u = m/s²) and gyroscope (u = rad/s)
/// reads a constant (gravity on +z, a small gyroscope bias) plus three
/// independent noises, in the continuous-time units of mpcal/noise.h:
/// - white noise of density N (u/√Hz): σ = N·√f_s per sample;
/// - bias instability B (u): flicker noise, two-sided PSD B²/(2πf),
///   approximated by a sum of first-order Gauss-Markov processes with
///   correlation times two per decade from `flicker_min_tau_s` to ten times
///   the record, each of variance B²·ln(√10)/π (the sum of equal-variance
///   processes evenly spaced in log T has PSD q/(f·ln r) one-sided between
///   the corners; Keshner 1982). Its Allan deviation is then flat at
///   0.664 B, within about 5 %, from about 10 `flicker_min_tau_s` to the
///   longest τ of the analysis (tests/noise/noise_terms_test.cc). Processes with T ≥ 100
///   sample periods are updated every T/(100 f_s⁻¹) samples and held in between (an error
///   below 1 %);
/// - a random walk of density K (u/s/√Hz): steps of K/√f_s per sample.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace mpcal {

/// The true terms of one axis (units of the file comment).
struct AxisNoiseTruth {
  double white_noise = 0.0;
  double bias_instability = 0.0;
  double random_walk = 0.0;
};

struct NoiseSimulationOptions {
  double duration_s = 3600.0;  ///< length of the record
  double rate_hz = 100.0;      ///< sample rate
  std::uint64_t seed = 1;      ///< the same record on every machine
  /// Per axis (x, y, z): accelerometer in m/s² (N m/s²/√Hz, B m/s²,
  /// K m/s³/√Hz) and gyroscope in rad/s (N rad/s/√Hz, B rad/s, K rad/s²/√Hz).
  std::array<AxisNoiseTruth, 3> accel_mps2{};
  std::array<AxisNoiseTruth, 3> gyro_radps{};
  /// Constant readings: the specific force at rest and the gyroscope bias.
  Eigen::Vector3d accel_mean_mps2{0.0, 0.0, 9.80665};
  Eigen::Vector3d gyro_mean_radps{1e-3, -2e-3, 5e-4};
  /// Shortest correlation time of the flicker approximation (s). Below
  /// about ten times this the bias instability rolls off (and rises like a
  /// random walk), so keep it where the white noise dominates.
  double flicker_min_tau_s = 0.1;

  std::string Validate() const;
};

/// Device classes with typical datasheet-order figures (not any one part):
/// "consumer" (phone/drone MEMS: 150 µg/√Hz, 0.7 °/√h, random walks that
/// show within an hour) and "industrial" (ADIS1646x-class: 23 µg/√Hz,
/// 0.15 °/√h, random walks that need most of a day). Each axis differs a
/// little from the others. std::nullopt for an unknown name.
std::optional<NoiseSimulationOptions> NoisePreset(std::string_view name);
/// The preset names, for messages.
std::vector<std::string> NoisePresetNames();

/// Generates the record row by row (memory independent of its length).
class NoiseGenerator {
 public:
  /// \throws mpcal::Error when options.Validate() fails.
  explicit NoiseGenerator(const NoiseSimulationOptions& options);
  ~NoiseGenerator();
  NoiseGenerator(const NoiseGenerator&) = delete;
  NoiseGenerator& operator=(const NoiseGenerator&) = delete;

  /// Number of rows: round(duration × rate).
  std::size_t rows() const;
  /// The next row (time from 0 s); false after the last.
  bool Next(double* t_s, Eigen::Vector3d* accel_mps2, Eigen::Vector3d* gyro_radps);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mpcal
