/// \file simulate_walk.h
/// \brief A synthetic field-verification walk with known truth (docs/method.md §5):
/// a closed, roughly rectangular loop walked with a sensor on a pole, the IMU
/// log of a device preset and a GNSS reference as an RTKLIB .pos file.
///
/// The walk: `rest_s` still at the start; then each side of the loop with a
/// smooth start (raised-cosine speed ramp over `ramp_s`), the walker's step
/// bob while cruising (vertical, along-track and sideways accelerations at the
/// step frequency), a smooth stop; `corner_stop_s` still at each corner;
/// `rest_s` still at the end, back at the start. Corners are jittered by up
/// to `corner_jitter_m` so the loop is only roughly rectangular.
///
/// The sensor: fixed to the pole with a small mounting tilt (`mount_tilt_deg`
/// about a random horizontal axis). Without `turn` the sensor keeps one
/// orientation all the way (the paper's setting); with `turn` the walker
/// stops at each corner and turns the pole with the new heading (a smooth
/// rotation over `turn_s` in the middle of the stop), and the log has
/// gyroscope columns.
///
/// Readings: specific force f in the sensor frame, reading =
/// device.truth.Forward(f) + white noise of the device's density
/// (σ = ND·√(rate/2)), quantised and clipped as the device; gyroscope = true
/// rate + a constant bias + white noise. The errors are the preset's (trial
/// 1; no turn-on redraw), so `truth` is exactly what corrects this log.
///
/// Clock: IMU and GNSS share one clock, seconds since 1970 on GPS time
/// (`start_time_s`), as an IMU stamped from the receiver.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mpcal/calibration.h"
#include "mpcal/gnss.h"
#include "mpcal/recording.h"
#include "mpcal/simulate.h"

namespace mpcal {

struct SimulateWalkOptions {
  /// The device (errors, noise, rate, range, resolution).
  DevicePreset device;
  /// Seeds every random draw (loop azimuth, corner jitter, tilt axis, noise).
  std::uint64_t seed = 1;
  /// Sides of the loop (m) and walking speed (m/s).
  double length_m = 40.0;
  double width_m = 25.0;
  double speed_mps = 1.2;
  /// Speed ramp at the start and end of each side (s).
  double ramp_s = 1.0;
  /// Step frequency (Hz) and the bob's acceleration amplitudes (m/s²):
  /// vertical and along-track at the step frequency, sideways at half of it.
  double step_hz = 1.8;
  double bob_vertical_mps2 = 2.0;
  double bob_along_mps2 = 1.0;
  double bob_sideways_mps2 = 0.5;
  /// Still at each corner (s), and at the start and at the end (s).
  double corner_stop_s = 3.0;
  double rest_s = 20.0;
  /// Corners moved by up to this (m), each coordinate, uniformly.
  double corner_jitter_m = 1.0;
  /// Tilt of the sensor's z axis from the vertical (degrees).
  double mount_tilt_deg = 0.1;
  /// Turn the sensor with the walker at each corner (gyroscope columns).
  bool turn = false;
  /// Duration of each turn (s), within the corner stop (which is extended
  /// to at least turn_s + 2 s).
  double turn_s = 2.5;
  /// Gyroscope: bias spread (1σ per axis, rad/s) and white-noise density
  /// (rad/s/√Hz).
  double gyro_bias_std_radps = 0.002;
  double gyro_noise_density_radps_per_sqrt_hz = 1e-4;
  /// GNSS: rate (Hz), 1σ noise horizontal and vertical (m).
  double gnss_rate_hz = 5.0;
  double gnss_noise_horizontal_m = 0.01;
  double gnss_noise_vertical_m = 0.02;
  /// Where the loop starts (WGS84).
  Geodetic origin{-25.4500, -49.2330, 935.0};
  /// Clock of the first IMU sample: seconds since 1970 on GPS time.
  double start_time_s = 1715508000.0;  // 2024-05-12 10:00:00
  /// 0 = the device's rate.
  double rate_hz = 0.0;

  /// "" when valid, otherwise a message naming the first bad field.
  std::string Validate() const;
};

struct SimulatedWalk {
  /// The IMU log in m/s² (gyroscope when turning), source "<simulated>".
  Recording recording;
  /// The true errors, as a calibration file holds them.
  Calibration truth;
  /// The GNSS reference, ready for FormatRtklibPos (GPST).
  std::vector<PosEpoch> gnss;
  /// The true path: east, north, up (m) from the start, at the IMU samples.
  std::vector<Eigen::Vector3d> true_enu_m;
  /// Length of the true horizontal path (m).
  double true_path_length_m = 0.0;
};

/// Simulates one walk.
/// \param gravity_mps2 local gravity magnitude (m/s²), stored in truth.
/// \throws mpcal::Error for invalid options or gravity.
SimulatedWalk SimulateWalk(const SimulateWalkOptions& options,
                           double gravity_mps2 = kStandardGravityMps2);

}  // namespace mpcal
