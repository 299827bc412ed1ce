// The steps of SimulateStatic (simulate.cc), private to the simulate room:
// the sample counts, the geometry of the session (orientations and hand
// turns), the true state at any time, the sensor's digitisation and the
// truth a calibration file would hold. Tests reach them through this header.
#pragma once

#include <array>
#include <cstddef>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "mpcal/simulate.h"
#include "simulate/random.h"

namespace mpcal::internal {

/// How many samples each part of the session has at the rate used.
struct StaticPlan {
  double rate_hz = 0.0;  ///< options.rate_hz, or the device's when 0
  std::size_t rest_n = 0;
  std::size_t turn_n = 0;
  std::size_t dwell_n = 0;
  std::size_t positions = 0;
  /// rest_n + positions × (turn_n + dwell_n).
  std::size_t total = 0;
};

/// Each duration × the rate, rounded to whole samples.
StaticPlan PlanStaticSession(const SimulateStaticOptions& options);

/// A sum of a few random sinusoids per axis: the hand's shake.
struct Shake {
  static constexpr int kTerms = 3;
  std::array<Eigen::Vector3d, kTerms> amplitude;
  std::array<Eigen::Vector3d, kTerms> phase_rad;
  std::array<double, kTerms> frequency_hz{};

  /// `rms` per axis, frequencies uniform in [f_lo_hz, f_hi_hz].
  static Shake Draw(double rms, double f_lo_hz, double f_hi_hz, PortableRandom& rng);
  Eigen::Vector3d At(double t_s) const;
};

/// One hand turn: minimum-jerk slerp from `from` to `to`, with shake that
/// fades in and out (sin² window) so that both ends join the still parts
/// smoothly in orientation, rate and acceleration.
struct Turn {
  double start_s = 0.0;
  double duration_s = 0.0;
  Eigen::Quaterniond from;
  Eigen::Quaterniond to;
  Shake accel;     // m/s², level frame
  Shake rotation;  // rad, sensor frame

  void At(double t_s,
          Eigen::Quaterniond& q_level_sensor,
          Eigen::Vector3d& accel_level) const;
};

/// The session's motion: a turn into each position, then its dwell.
struct StaticGeometry {
  std::vector<Turn> turns;
  /// The true "up" of each position, seen from the sensor.
  std::vector<Eigen::Vector3d> directions;
  /// [begin, end) samples of each dwell.
  std::vector<std::pair<std::size_t, std::size_t>> still_ranges;

  /// The true orientation (sensor to level) and level acceleration at t_s:
  /// still before the first turn and after each turn's end. Turns are
  /// continuous in time, so that the gyroscope's central differences may
  /// straddle a segment boundary.
  void StateAt(double t_s, Eigen::Quaterniond& q, Eigen::Vector3d& accel) const;
};

/// Directions, headings and shakes, all drawn from the one geometry stream in
/// a fixed order (so that the noise options do not move the positions): the
/// first 26 positions are the cube's directions tilted by up to tilt_deg, the
/// others random.
StaticGeometry DrawStaticGeometry(const SimulateStaticOptions& options,
                                  const StaticPlan& plan);

/// An accelerometer reading in m/s² as the device gives it: rounded to its
/// resolution, clipped to its range (0: none), then in `units` (counts: the
/// ADC's offset and scale, rounded to whole counts).
Eigen::Vector3d DigitiseAccel(Eigen::Vector3d y_mps2,
                              const DevicePreset& device,
                              const SimulateStaticOptions& options);

/// The truth as a calibration file holds it, such that truth.Correct(reading)
/// is the specific force: the device's model, the units' scale (counts: the
/// ADC offset folded into the bias), the bias drift referred to the last
/// sample, and the gyroscope's when simulated.
Calibration StaticTruth(const SimulateStaticOptions& options,
                        const StaticPlan& plan,
                        double gravity_mps2);

}  // namespace mpcal::internal
