// The steps of SimulateStatic (static_steps.h).
#include "simulate/static_steps.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "mpcal/units.h"

namespace mpcal::internal {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegToRad = kPi / 180.0;
// The geometry's stream, drawn from the seed (simulate.cc has the others).
constexpr std::uint64_t kGeometryStream = 0x67656f6d65747279ull;

// Rotates `u` by an angle uniform in [0, max_rad] about a random axis
// perpendicular to it: a hand never holds a face exactly down.
Eigen::Vector3d Tilt(const Eigen::Vector3d& u, double max_rad, PortableRandom& rng) {
  Eigen::Vector3d axis;
  do {
    axis = u.cross(rng.UnitVector());
  } while (axis.norm() < 1e-3);
  axis.normalize();
  const double angle = rng.Uniform(0.0, max_rad);
  return (Eigen::AngleAxisd(angle, axis) * u).normalized();
}

// Sensor-to-level orientation whose "up" seen from the sensor is `direction`,
// with a random heading (gravity cannot see it, but the turns can).
Eigen::Quaterniond OrientationFor(const Eigen::Vector3d& direction, PortableRandom& rng) {
  const Eigen::Quaterniond align =
      Eigen::Quaterniond::FromTwoVectors(direction, Eigen::Vector3d::UnitZ());
  const double heading = rng.Uniform(-kPi, kPi);
  return (Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()) * align).normalized();
}

}  // namespace

StaticPlan PlanStaticSession(const SimulateStaticOptions& options) {
  StaticPlan plan;
  plan.rate_hz = options.rate_hz > 0 ? options.rate_hz : options.device.rate_hz;
  const auto samples = [&](double s) {
    return static_cast<std::size_t>(std::llround(s * plan.rate_hz));
  };
  plan.rest_n = samples(options.initial_rest_s);
  plan.turn_n = samples(options.turn_s);
  plan.dwell_n = samples(options.dwell_s);
  plan.positions = static_cast<std::size_t>(options.positions);
  plan.total = plan.rest_n + plan.positions * (plan.turn_n + plan.dwell_n);
  return plan;
}

Shake Shake::Draw(double rms, double f_lo_hz, double f_hi_hz, PortableRandom& rng) {
  Shake s;
  // Each term contributes amplitude²/2 of variance per axis.
  const double per_term = rms * std::sqrt(2.0 / kTerms);
  for (int j = 0; j < kTerms; ++j) {
    const auto t = static_cast<std::size_t>(j);
    s.amplitude[t] = rng.Normal3() * per_term;
    for (int k = 0; k < 3; ++k) s.phase_rad[t][k] = rng.Uniform(0.0, 2.0 * kPi);
    s.frequency_hz[t] = rng.Uniform(f_lo_hz, f_hi_hz);
  }
  return s;
}

Eigen::Vector3d Shake::At(double t_s) const {
  Eigen::Vector3d v = Eigen::Vector3d::Zero();
  for (std::size_t j = 0; j < kTerms; ++j) {
    for (int k = 0; k < 3; ++k) {
      v[k] +=
          amplitude[j][k] * std::sin(2.0 * kPi * frequency_hz[j] * t_s + phase_rad[j][k]);
    }
  }
  return v;
}

void Turn::At(double t_s,
              Eigen::Quaterniond& q_level_sensor,
              Eigen::Vector3d& accel_level) const {
  const double tau = std::clamp((t_s - start_s) / duration_s, 0.0, 1.0);
  const double s = tau * tau * tau * (10.0 + tau * (-15.0 + 6.0 * tau));
  const double sin_tau = std::sin(kPi * tau);
  const double window = sin_tau * sin_tau;
  const double local_s = t_s - start_s;
  const Eigen::Vector3d wobble = window * rotation.At(local_s);
  const double angle = wobble.norm();
  Eigen::Quaterniond q = from.slerp(s, to);
  if (angle > 0.0) q = q * Eigen::Quaterniond(Eigen::AngleAxisd(angle, wobble / angle));
  q_level_sensor = q.normalized();
  accel_level = window * accel.At(local_s);
}

void StaticGeometry::StateAt(double t_s,
                             Eigen::Quaterniond& q,
                             Eigen::Vector3d& accel) const {
  const auto first_after =
      std::upper_bound(turns.begin(), turns.end(), t_s, [](double t, const Turn& turn) {
        return t < turn.start_s;
      });
  if (first_after == turns.begin()) {
    q = turns.front().from;
    accel.setZero();
    return;
  }
  const Turn& turn = *(first_after - 1);
  if (t_s >= turn.start_s + turn.duration_s) {
    q = turn.to;
    accel.setZero();
    return;
  }
  turn.At(t_s, q, accel);
}

StaticGeometry DrawStaticGeometry(const SimulateStaticOptions& options,
                                  const StaticPlan& plan) {
  StaticGeometry geometry;
  PortableRandom rng(SplitMix64(options.seed ^ kGeometryStream));
  const double tilt_rad = options.tilt_deg * kDegToRad;
  const std::vector<Eigen::Vector3d> cube = CubeDirections26();
  const Eigen::Vector3d rest_direction = Tilt(Eigen::Vector3d::UnitZ(), tilt_rad, rng);
  Eigen::Quaterniond previous = OrientationFor(rest_direction, rng);
  std::vector<Eigen::Quaterniond> orientations;
  for (std::size_t k = 0; k < plan.positions; ++k) {
    const Eigen::Vector3d u =
        k < cube.size() ? Tilt(cube[k], tilt_rad, rng) : rng.UnitVector();
    geometry.directions.push_back(u);
    orientations.push_back(OrientationFor(u, rng));
  }
  std::size_t index = plan.rest_n;
  for (std::size_t k = 0; k < plan.positions; ++k) {
    Turn turn;
    turn.start_s = static_cast<double>(index) / plan.rate_hz;
    turn.duration_s = static_cast<double>(plan.turn_n) / plan.rate_hz;
    turn.from = previous;
    turn.to = orientations[k];
    turn.accel = Shake::Draw(options.shake_accel_mps2, 1.0, 6.0, rng);
    turn.rotation = Shake::Draw(options.shake_rotation_deg * kDegToRad, 3.0, 9.0, rng);
    geometry.turns.push_back(turn);
    index += plan.turn_n;
    geometry.still_ranges.emplace_back(index, index + plan.dwell_n);
    index += plan.dwell_n;
    previous = orientations[k];
  }
  return geometry;
}

Eigen::Vector3d DigitiseAccel(Eigen::Vector3d y_mps2,
                              const DevicePreset& device,
                              const SimulateStaticOptions& options) {
  const double res = device.resolution_mps2;
  const double range = device.range_mps2;
  if (res > 0) y_mps2 = (y_mps2 / res).array().round().matrix() * res;
  if (range > 0) y_mps2 = y_mps2.cwiseMax(-range).cwiseMin(range);
  switch (options.units) {
    case AccelUnits::kMps2:
      break;
    case AccelUnits::kG:
      y_mps2 /= kStandardGravityMps2;
      break;
    case AccelUnits::kCounts:
      y_mps2 = (Eigen::Vector3d::Constant(options.counts_offset) +
                y_mps2 * options.counts_per_mps2)
                   .array()
                   .round()
                   .matrix();
      break;
  }
  return y_mps2;
}

Calibration StaticTruth(const SimulateStaticOptions& options,
                        const StaticPlan& plan,
                        double gravity_mps2) {
  const DevicePreset& device = options.device;
  Calibration truth;
  truth.model_kind = ModelKind::kShinElSheimy9;
  truth.gravity_mps2 = gravity_mps2;
  truth.input_units = options.units;
  truth.model = device.truth;
  switch (options.units) {
    case AccelUnits::kMps2:
      truth.mps2_per_unit = 1.0;
      break;
    case AccelUnits::kG:
      truth.mps2_per_unit = kStandardGravityMps2;
      break;
    case AccelUnits::kCounts:
      truth.mps2_per_unit = 1.0 / options.counts_per_mps2;
      truth.model.bias_mps2 +=
          Eigen::Vector3d::Constant(options.counts_offset / options.counts_per_mps2);
      break;
  }
  if (!options.bias_drift_mps2_per_s.isZero()) {
    BiasDrift drift;
    drift.mps2_per_s = options.bias_drift_mps2_per_s;
    drift.reference_time_s = static_cast<double>(plan.total - 1) / plan.rate_hz;
    truth.bias_drift = drift;
  }
  if (options.gyro) {
    GyroCalibration gyro;
    gyro.input_units = options.gyro_units;
    gyro.m = device.gyro_m;
    gyro.bias_radps = device.gyro_bias_radps;
    if (options.gyro_units == GyroUnits::kCounts) {
      gyro.radps_per_unit = 1.0 / options.gyro_counts_per_radps;
      gyro.bias_radps += Eigen::Vector3d::Constant(options.gyro_counts_offset /
                                                   options.gyro_counts_per_radps);
    }
    truth.gyroscope = gyro;
  }
  return truth;
}

}  // namespace mpcal::internal
