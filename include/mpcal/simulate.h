/// \file simulate.h
/// \brief Synthetic hand-held sessions with known truth, for tests, the demo
/// and the benchmarks. Presets follow the paper's devices (METHOD.md §6).
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mpcal/calibration.h"
#include "mpcal/model.h"
#include "mpcal/recording.h"

namespace mpcal {

/// A device: its true errors and its noise.
struct DevicePreset {
  std::string name;
  ErrorModel truth;
  double noise_density_mps2_per_sqrt_hz = 0.0;
  double rate_hz = 100.0;
  /// Measurement range (± m/s²); 0 = unlimited.
  double range_mps2 = 0.0;
  /// Quantisation step (m/s²); 0 = none.
  double resolution_mps2 = 0.0;
  /// Spread of the bias from one power-up to the next (1σ, m/s² per axis).
  Eigen::Vector3d turn_on_bias_std_mps2 = Eigen::Vector3d::Zero();
};

/// "colibri", "inertiacube3", "mti-g".
/// \throws mpcal::Error for an unknown name (the message lists the known).
DevicePreset FindPreset(const std::string& name);
std::vector<std::string> PresetNames();

/// The 26 cube directions of Syed et al. (2007) (faces, edges, corners), unit
/// vectors of the gravity reaction in the sensor frame.
std::vector<Eigen::Vector3d> CubeDirections26();

struct SimulateStaticOptions {
  DevicePreset device;
  std::uint64_t seed = 1;
  /// Number of positions: the first `positions` of the 26 cube directions
  /// (faces first), each tilted randomly by up to `tilt_deg`.
  int positions = 26;
  double tilt_deg = 5.0;
  double dwell_s = 10.0;       ///< still time per position
  double turn_s = 2.0;         ///< hand turn between positions
  double initial_rest_s = 10.0;
  /// 0 = the device's rate.
  double rate_hz = 0.0;
  /// Units written: readings divided by g for kG; for kCounts, an ADC with
  /// zero at `counts_offset` and `counts_per_mps2`.
  AccelUnits units = AccelUnits::kMps2;
  double counts_offset = 32768.0;
  double counts_per_mps2 = 400.0;
  std::string Validate() const;
};

struct SimulatedSession {
  Recording recording;
  /// The truth as a calibration file (model, gravity, units).
  Calibration truth;
  /// Sample ranges [begin, end) of the still part of each position, and its
  /// true direction, in order (the initial rest is not a position here).
  std::vector<std::pair<std::size_t, std::size_t>> still_ranges;
  std::vector<Eigen::Vector3d> directions;
};

/// \throws mpcal::Error for invalid options.
SimulatedSession SimulateStatic(const SimulateStaticOptions& options,
                                double gravity_mps2 = 9.80665);

}  // namespace mpcal
