// Hand-held static sessions with known truth (simulate.h).
#include "mpcal/simulate.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <utility>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include "mpcal/error.h"
#include "mpcal/units.h"
#include "random.h"

namespace mpcal {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegToRad = kPi / 180.0;
// Beyond this a session would need gigabytes; nobody holds a sensor that long.
constexpr double kMaxSamples = 2e7;

// Independent random streams drawn from one seed: changing the noise (or
// turning the gyroscope on) must not move the positions, and vice versa.
constexpr std::uint64_t kGeometryStream = 0x67656f6d65747279ull;
constexpr std::uint64_t kNoiseStream = 0x6e6f697365616363ull;
constexpr std::uint64_t kGyroStream = 0x6e6f69736567796full;
constexpr std::uint64_t kTrialBiasStream = 0x747269616c626961ull;

using internal::SplitMix64;
using Random = internal::PortableRandom;

// Rotates `u` by an angle uniform in [0, max_rad] about a random axis
// perpendicular to it: a hand never holds a face exactly down.
Eigen::Vector3d Tilt(const Eigen::Vector3d& u, double max_rad, Random& rng) {
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
Eigen::Quaterniond OrientationFor(const Eigen::Vector3d& direction, Random& rng) {
  const Eigen::Quaterniond align =
      Eigen::Quaterniond::FromTwoVectors(direction, Eigen::Vector3d::UnitZ());
  const double heading = rng.Uniform(-kPi, kPi);
  return (Eigen::AngleAxisd(heading, Eigen::Vector3d::UnitZ()) * align).normalized();
}

// A sum of a few random sinusoids per axis: the hand's shake.
struct Shake {
  static constexpr int kTerms = 3;
  Eigen::Vector3d amplitude[kTerms];
  Eigen::Vector3d phase_rad[kTerms];
  double frequency_hz[kTerms] = {};

  static Shake Draw(double rms, double f_lo_hz, double f_hi_hz, Random& rng) {
    Shake s;
    // Each term contributes amplitude²/2 of variance per axis.
    const double per_term = rms * std::sqrt(2.0 / kTerms);
    for (int j = 0; j < kTerms; ++j) {
      s.amplitude[j] = rng.Normal3() * per_term;
      for (int k = 0; k < 3; ++k) s.phase_rad[j][k] = rng.Uniform(0.0, 2.0 * kPi);
      s.frequency_hz[j] = rng.Uniform(f_lo_hz, f_hi_hz);
    }
    return s;
  }
  Eigen::Vector3d At(double t_s) const {
    Eigen::Vector3d v = Eigen::Vector3d::Zero();
    for (int j = 0; j < kTerms; ++j) {
      for (int k = 0; k < 3; ++k) {
        v[k] += amplitude[j][k] *
                std::sin(2.0 * kPi * frequency_hz[j] * t_s + phase_rad[j][k]);
      }
    }
    return v;
  }
};

// One hand turn: minimum-jerk slerp from `from` to `to`, with shake that
// fades in and out (sin² window) so that both ends join the still parts
// smoothly in orientation, rate and acceleration.
struct Turn {
  double start_s = 0.0;
  double duration_s = 0.0;
  Eigen::Quaterniond from;
  Eigen::Quaterniond to;
  Shake accel;     // m/s², level frame
  Shake rotation;  // rad, sensor frame

  void At(double t_s,
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
};

std::string CheckFinite(double v, const char* field) {
  if (!std::isfinite(v))
    return fmt::format("{} must be a finite number (got {})", field, v);
  return "";
}

}  // namespace

std::vector<Eigen::Vector3d> CubeDirections26() {
  std::vector<Eigen::Vector3d> d;
  d.reserve(26);
  // Faces.
  for (int axis = 0; axis < 3; ++axis) {
    for (const double sign : {1.0, -1.0}) {
      Eigen::Vector3d v = Eigen::Vector3d::Zero();
      v[axis] = sign;
      d.push_back(v);
    }
  }
  // Edges: two axes non-zero.
  const double e = 1.0 / std::sqrt(2.0);
  for (int zero_axis = 2; zero_axis >= 0; --zero_axis) {
    const int a = zero_axis == 0 ? 1 : 0;
    const int b = zero_axis == 2 ? 1 : 2;
    for (const double sa : {1.0, -1.0}) {
      for (const double sb : {1.0, -1.0}) {
        Eigen::Vector3d v = Eigen::Vector3d::Zero();
        v[a] = sa * e;
        v[b] = sb * e;
        d.push_back(v);
      }
    }
  }
  // Corners.
  const double c = 1.0 / std::sqrt(3.0);
  for (const double sx : {1.0, -1.0}) {
    for (const double sy : {1.0, -1.0}) {
      for (const double sz : {1.0, -1.0}) d.emplace_back(sx * c, sy * c, sz * c);
    }
  }
  return d;
}

std::string SimulateStaticOptions::Validate() const {
  const DevicePreset& dev = device;
  if (!bias_drift_mps2_per_s.allFinite()) return "bias_drift_mps2_per_s must be finite";
  for (const auto& [value, name] :
       {std::pair{dev.noise_density_mps2_per_sqrt_hz,
                  "device.noise_density_mps2_per_sqrt_hz"},
        std::pair{dev.rate_hz, "device.rate_hz"},
        std::pair{dev.range_mps2, "device.range_mps2"},
        std::pair{dev.resolution_mps2, "device.resolution_mps2"},
        std::pair{tilt_deg, "tilt_deg"},
        std::pair{dwell_s, "dwell_s"},
        std::pair{turn_s, "turn_s"},
        std::pair{initial_rest_s, "initial_rest_s"},
        std::pair{rate_hz, "rate_hz"},
        std::pair{shake_accel_mps2, "shake_accel_mps2"},
        std::pair{shake_rotation_deg, "shake_rotation_deg"},
        std::pair{gyro_noise_density_radps_per_sqrt_hz,
                  "gyro_noise_density_radps_per_sqrt_hz"},
        std::pair{dev.gyro_noise_density_radps_per_sqrt_hz,
                  "device.gyro_noise_density_radps_per_sqrt_hz"},
        std::pair{dev.gyro_bias_walk_radps_per_sqrt_s,
                  "device.gyro_bias_walk_radps_per_sqrt_s"},
        std::pair{gyro_counts_offset, "gyro_counts_offset"},
        std::pair{gyro_counts_per_radps, "gyro_counts_per_radps"},
        std::pair{counts_offset, "counts_offset"},
        std::pair{counts_per_mps2, "counts_per_mps2"}}) {
    if (std::string e = CheckFinite(value, name); !e.empty()) return e;
  }
  if (!dev.truth.bias_mps2.allFinite() || !dev.truth.scale_factor_error.allFinite() ||
      !std::isfinite(dev.truth.theta_yz_rad) || !std::isfinite(dev.truth.theta_zx_rad) ||
      !std::isfinite(dev.truth.theta_zy_rad)) {
    return "device.truth has a non-finite parameter";
  }
  if ((dev.truth.scale_factor_error.array() <= -0.5).any()) {
    return "device.truth.scale_factor_error must be greater than -0.5 on every axis";
  }
  for (const double theta :
       {dev.truth.theta_yz_rad, dev.truth.theta_zx_rad, dev.truth.theta_zy_rad}) {
    if (std::abs(theta) >= 0.5) {
      return fmt::format(
          "device.truth non-orthogonality angles must be below 0.5 rad "
          "(got {})",
          theta);
    }
  }
  if (!dev.turn_on_bias_std_mps2.allFinite() ||
      (dev.turn_on_bias_std_mps2.array() < 0).any()) {
    return "device.turn_on_bias_std_mps2 must be finite and non-negative";
  }
  if (dev.noise_density_mps2_per_sqrt_hz < 0) {
    return fmt::format("noise density must not be negative (got {} m/s²/√Hz)",
                       dev.noise_density_mps2_per_sqrt_hz);
  }
  if (dev.range_mps2 < 0)
    return fmt::format("device.range_mps2 must be ≥ 0 (got {})", dev.range_mps2);
  if (dev.resolution_mps2 < 0) {
    return fmt::format("device.resolution_mps2 must be ≥ 0 (got {})",
                       dev.resolution_mps2);
  }
  if (rate_hz < 0)
    return fmt::format("rate_hz must be positive, or 0 for the device's (got {})",
                       rate_hz);
  const double rate = rate_hz > 0 ? rate_hz : dev.rate_hz;
  if (rate <= 0) return fmt::format("sample rate must be positive (got {} Hz)", rate);
  if (positions < 1)
    return fmt::format("positions must be at least 1 (got {})", positions);
  if (tilt_deg < 0 || tilt_deg > 90) {
    return fmt::format("tilt_deg must be between 0 and 90 degrees (got {})", tilt_deg);
  }
  if (dwell_s <= 0) return fmt::format("dwell_s must be positive (got {} s)", dwell_s);
  if (std::llround(dwell_s * rate) < 2) {
    return fmt::format(
        "dwell_s = {} s gives fewer than 2 samples at {} Hz; hold longer", dwell_s, rate);
  }
  if (turn_s <= 0) return fmt::format("turn_s must be positive (got {} s)", turn_s);
  if (std::llround(turn_s * rate) < 2) {
    return fmt::format("turn_s = {} s gives fewer than 2 samples at {} Hz", turn_s, rate);
  }
  if (initial_rest_s < 0) {
    return fmt::format("initial_rest_s must not be negative (got {} s)", initial_rest_s);
  }
  if (shake_accel_mps2 < 0) return "shake_accel_mps2 must not be negative";
  if (shake_rotation_deg < 0) return "shake_rotation_deg must not be negative";
  if (dev.gyro_noise_density_radps_per_sqrt_hz < 0) {
    return "device.gyro_noise_density_radps_per_sqrt_hz must not be negative";
  }
  if (dev.gyro_bias_walk_radps_per_sqrt_s < 0) {
    return "device.gyro_bias_walk_radps_per_sqrt_s must not be negative";
  }
  if (!dev.gyro_m.allFinite() || !dev.gyro_bias_radps.allFinite()) {
    return "device.gyro_m and device.gyro_bias_radps must be finite";
  }
  if (std::abs(dev.gyro_m.determinant()) < 1e-3) {
    return "device.gyro_m must be invertible (a scale near 1 on each axis)";
  }
  if (gyro_counts_per_radps <= 0) {
    return fmt::format("gyro_counts_per_radps must be positive (got {})",
                       gyro_counts_per_radps);
  }
  if (earth_rate_latitude_deg && !(std::abs(*earth_rate_latitude_deg) <= 90.0)) {
    return "earth_rate_latitude_deg must be between -90 and 90";
  }
  if (counts_per_mps2 <= 0) {
    return fmt::format("counts_per_mps2 must be positive (got {})", counts_per_mps2);
  }
  const double samples = (initial_rest_s + positions * (turn_s + dwell_s)) * rate;
  if (samples > kMaxSamples) {
    return fmt::format(
        "the session would have {:.3g} samples ((initial rest + positions × "
        "(turn + dwell)) × rate); the limit is {:.0e}: use fewer positions, "
        "a shorter dwell or a lower rate",
        samples,
        kMaxSamples);
  }
  return "";
}

SimulatedSession SimulateStatic(const SimulateStaticOptions& options,
                                double gravity_mps2) {
  if (const std::string problem = options.Validate(); !problem.empty()) {
    throw Error("invalid simulation options: " + problem);
  }
  if (!std::isfinite(gravity_mps2) || gravity_mps2 <= 0) {
    throw Error(
        fmt::format("gravity must be positive and finite (got {} m/s²)", gravity_mps2));
  }
  const DevicePreset& device = options.device;
  const double rate = options.rate_hz > 0 ? options.rate_hz : device.rate_hz;
  const auto rest_n =
      static_cast<std::size_t>(std::llround(options.initial_rest_s * rate));
  const auto turn_n = static_cast<std::size_t>(std::llround(options.turn_s * rate));
  const auto dwell_n = static_cast<std::size_t>(std::llround(options.dwell_s * rate));
  const auto positions = static_cast<std::size_t>(options.positions);
  const std::size_t total = rest_n + positions * (turn_n + dwell_n);

  SimulatedSession session;
  session.rate_hz = rate;

  // Geometry first, all from one stream: directions, headings, shakes.
  Random geometry(SplitMix64(options.seed ^ kGeometryStream));
  const double tilt_rad = options.tilt_deg * kDegToRad;
  const std::vector<Eigen::Vector3d> cube = CubeDirections26();
  const Eigen::Vector3d rest_direction =
      Tilt(Eigen::Vector3d::UnitZ(), tilt_rad, geometry);
  Eigen::Quaterniond previous = OrientationFor(rest_direction, geometry);
  std::vector<Eigen::Quaterniond> orientations;
  for (std::size_t k = 0; k < positions; ++k) {
    const Eigen::Vector3d u =
        k < cube.size() ? Tilt(cube[k], tilt_rad, geometry) : geometry.UnitVector();
    session.directions.push_back(u);
    orientations.push_back(OrientationFor(u, geometry));
  }
  std::vector<Turn> turns;
  std::size_t index = rest_n;
  for (std::size_t k = 0; k < positions; ++k) {
    Turn turn;
    turn.start_s = static_cast<double>(index) / rate;
    turn.duration_s = static_cast<double>(turn_n) / rate;
    turn.from = previous;
    turn.to = orientations[k];
    turn.accel = Shake::Draw(options.shake_accel_mps2, 1.0, 6.0, geometry);
    turn.rotation =
        Shake::Draw(options.shake_rotation_deg * kDegToRad, 3.0, 9.0, geometry);
    turns.push_back(turn);
    index += turn_n;
    session.still_ranges.emplace_back(index, index + dwell_n);
    index += dwell_n;
    previous = orientations[k];
  }

  // The true state at any time: which segment, then orientation and level
  // acceleration. Turns are continuous in time, so the gyroscope's central
  // differences may straddle a segment boundary.
  const Eigen::Quaterniond rest_orientation = turns.front().from;
  auto state_at = [&](double t_s, Eigen::Quaterniond& q, Eigen::Vector3d& accel) {
    const auto first_after =
        std::upper_bound(turns.begin(), turns.end(), t_s, [](double t, const Turn& turn) {
          return t < turn.start_s;
        });
    if (first_after == turns.begin()) {
      q = rest_orientation;
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
  };

  const ErrorModel& model = device.truth;
  const double sigma = device.noise_density_mps2_per_sqrt_hz * std::sqrt(rate / 2.0);
  session.noise_std_mps2 = Eigen::Vector3d::Constant(sigma);
  const double gyro_density = options.gyro_noise_density_radps_per_sqrt_hz >= 0
                                  ? options.gyro_noise_density_radps_per_sqrt_hz
                                  : device.gyro_noise_density_radps_per_sqrt_hz;
  const double gyro_sigma = gyro_density * std::sqrt(rate / 2.0);
  const Eigen::Matrix3d gyro_m_inverse = device.gyro_m.inverse();
  // The bias walks from its value at time 0 (the truth's), one step per sample.
  const double walk_step = device.gyro_bias_walk_radps_per_sqrt_s / std::sqrt(rate);
  Eigen::Vector3d gyro_bias = device.gyro_bias_radps;
  Eigen::Vector3d earth_level = Eigen::Vector3d::Zero();
  if (options.earth_rate_latitude_deg) {
    constexpr double kEarthRateRadps = 7.292115e-5;
    const double lat = *options.earth_rate_latitude_deg * kDegToRad;
    earth_level = kEarthRateRadps * Eigen::Vector3d(0.0, std::cos(lat), std::sin(lat));
  }
  Random noise(SplitMix64(options.seed ^ kNoiseStream));
  Random gyro_noise(SplitMix64(options.seed ^ kGyroStream));
  const double res = device.resolution_mps2;
  const double range = device.range_mps2;
  const Eigen::Vector3d up_level(0.0, 0.0, gravity_mps2);
  // A gyroscope's output is its rate low-pass filtered to the output rate:
  // here the mean rate over the sample period centred on the sample (the
  // rotation over it, over its length), as a delta-angle output is.
  const double half_step_s = 0.5 / rate;

  Recording& rec = session.recording;
  rec.units = options.units;
  rec.source = "<simulated>";
  rec.time_s.resize(total);
  rec.accel.resize(total);
  if (options.gyro) {
    rec.gyro_radps.resize(total);
    rec.gyro_units = options.gyro_units;
    session.true_rate_radps.resize(total);
    session.gyro_noise_std_radps = gyro_sigma;
  }
  for (std::size_t i = 0; i < total; ++i) {
    const double t = static_cast<double>(i) / rate;
    rec.time_s[i] = t;
    Eigen::Quaterniond q_level_sensor;
    Eigen::Vector3d accel_level;
    state_at(t, q_level_sensor, accel_level);
    // Specific force: what an ideal accelerometer senses, in the sensor frame.
    const Eigen::Vector3d f = q_level_sensor.conjugate() * (accel_level + up_level);
    Eigen::Vector3d y = model.Forward(f) + sigma * noise.Normal3();
    y += options.bias_drift_mps2_per_s * (t - static_cast<double>(total - 1) / rate);
    if (res > 0) y = (y / res).array().round().matrix() * res;
    if (range > 0) y = y.cwiseMax(-range).cwiseMin(range);
    switch (options.units) {
      case AccelUnits::kMps2:
        break;
      case AccelUnits::kG:
        y /= kStandardGravityMps2;
        break;
      case AccelUnits::kCounts:
        y = (Eigen::Vector3d::Constant(options.counts_offset) +
             y * options.counts_per_mps2)
                .array()
                .round()
                .matrix();
        break;
    }
    rec.accel[i] = y;
    if (options.gyro) {
      Eigen::Quaterniond q0, q1;
      Eigen::Vector3d unused;
      state_at(t - half_step_s, q0, unused);
      state_at(t + half_step_s, q1, unused);
      const Eigen::AngleAxisd delta((q0.conjugate() * q1).normalized());
      const Eigen::Vector3d rate_radps =
          delta.angle() * delta.axis() / (2.0 * half_step_s) +
          q_level_sensor.conjugate() * earth_level;
      session.true_rate_radps[i] = rate_radps;
      Eigen::Vector3d g =
          gyro_m_inverse * rate_radps + gyro_bias + gyro_sigma * gyro_noise.Normal3();
      if (walk_step > 0) gyro_bias += walk_step * gyro_noise.Normal3();
      if (options.gyro_units == GyroUnits::kCounts) {
        g = (Eigen::Vector3d::Constant(options.gyro_counts_offset) +
             g * options.gyro_counts_per_radps)
                .array()
                .round()
                .matrix();
      }
      rec.gyro_radps[i] = g;
    }
  }

  // The truth, such that truth.Correct(reading) is the specific force.
  Calibration& truth = session.truth;
  truth.model_kind = ModelKind::kShinElSheimy9;
  truth.gravity_mps2 = gravity_mps2;
  truth.input_units = options.units;
  truth.model = model;
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
    drift.reference_time_s = static_cast<double>(total - 1) / rate;
    truth.bias_drift = drift;
  }
  double step = res;
  if (options.units == AccelUnits::kCounts)
    step = std::max(step, 1.0 / options.counts_per_mps2);
  session.quantisation_step_mps2 = step;
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
  Provenance provenance;
  provenance.input = "<simulated>";
  provenance.options = fmt::format(
      "simulate static: device {}, seed {}, positions {}, dwell {} s, turn {} s, rate {} "
      "Hz, "
      "noise density {} m/s²/√Hz, units {}",
      device.name.empty() ? "custom" : device.name,
      options.seed,
      options.positions,
      options.dwell_s,
      options.turn_s,
      rate,
      device.noise_density_mps2_per_sqrt_hz,
      ToString(options.units));
  truth.provenance = provenance;
  return session;
}

std::uint64_t TrialSeed(std::uint64_t base_seed, int trial) {
  return SplitMix64(SplitMix64(base_seed) + static_cast<std::uint64_t>(trial));
}

std::vector<SimulateStaticOptions> TrialOptions(const SimulateStaticOptions& options,
                                                int trials) {
  if (trials < 1) throw Error(fmt::format("trials must be at least 1 (got {})", trials));
  if (const std::string problem = options.Validate(); !problem.empty()) {
    throw Error("invalid simulation options: " + problem);
  }
  Random bias_rng(SplitMix64(options.seed ^ kTrialBiasStream));
  std::vector<SimulateStaticOptions> result;
  result.reserve(static_cast<std::size_t>(trials));
  for (int i = 1; i <= trials; ++i) {
    SimulateStaticOptions trial = options;
    trial.seed = TrialSeed(options.seed, i);
    trial.device.truth.bias_mps2 +=
        options.device.turn_on_bias_std_mps2.cwiseProduct(bias_rng.Normal3());
    result.push_back(std::move(trial));
  }
  return result;
}

std::vector<SimulatedSession> SimulateTrials(const SimulateStaticOptions& options,
                                             int trials,
                                             double gravity_mps2) {
  std::vector<SimulatedSession> sessions;
  for (const SimulateStaticOptions& trial : TrialOptions(options, trials)) {
    sessions.push_back(SimulateStatic(trial, gravity_mps2));
  }
  return sessions;
}

}  // namespace mpcal
