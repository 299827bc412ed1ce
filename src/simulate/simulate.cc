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
#include "simulate/random.h"
#include "simulate/static_steps.h"

namespace mpcal {
namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kDegToRad = kPi / 180.0;
// Beyond this a session would need gigabytes; nobody holds a sensor that long.
constexpr double kMaxSamples = 2e7;

// Independent random streams drawn from one seed: changing the noise (or
// turning the gyroscope on) must not move the positions, and vice versa.
constexpr std::uint64_t kNoiseStream = 0x6e6f697365616363ull;
constexpr std::uint64_t kGyroStream = 0x6e6f69736567796full;
constexpr std::uint64_t kTrialBiasStream = 0x747269616c626961ull;

using internal::SplitMix64;
using Random = internal::PortableRandom;

// The gyroscope of a static session: the true rate from the orientation
// half a sample either side, the device's misalignment, bias (walking one
// step per sample from its value at time 0), white noise and ADC.
class GyroSampler {
 public:
  GyroSampler(const SimulateStaticOptions& options, double rate_hz)
      : options_(options),
        m_inverse_(options.device.gyro_m.inverse()),
        bias_(options.device.gyro_bias_radps),
        walk_step_(options.device.gyro_bias_walk_radps_per_sqrt_s / std::sqrt(rate_hz)),
        half_step_s_(0.5 / rate_hz),
        noise_(SplitMix64(options.seed ^ kGyroStream)) {
    const double density = options.gyro_noise_density_radps_per_sqrt_hz >= 0
                               ? options.gyro_noise_density_radps_per_sqrt_hz
                               : options.device.gyro_noise_density_radps_per_sqrt_hz;
    sigma_ = density * std::sqrt(rate_hz / 2.0);
    if (options.earth_rate_latitude_deg) {
      constexpr double kEarthRateRadps = 7.292115e-5;
      const double lat = *options.earth_rate_latitude_deg * kDegToRad;
      earth_level_ = kEarthRateRadps * Eigen::Vector3d(0.0, std::cos(lat), std::sin(lat));
    }
  }

  double sigma_radps() const { return sigma_; }

  // The reading at t (rad/s or counts) and the true rate (rad/s, body frame).
  // A gyroscope's output is its rate low-pass filtered to the output rate:
  // here the mean rate over the sample period centred on the sample (the
  // rotation over it, over its length), as a delta-angle output is.
  Eigen::Vector3d Sample(const internal::StaticGeometry& geometry,
                         double t_s,
                         const Eigen::Quaterniond& q_level_sensor,
                         Eigen::Vector3d& true_rate_radps) {
    Eigen::Quaterniond q0;
    Eigen::Quaterniond q1;
    Eigen::Vector3d unused;
    geometry.StateAt(t_s - half_step_s_, q0, unused);
    geometry.StateAt(t_s + half_step_s_, q1, unused);
    const Eigen::AngleAxisd delta((q0.conjugate() * q1).normalized());
    true_rate_radps = delta.angle() * delta.axis() / (2.0 * half_step_s_) +
                      q_level_sensor.conjugate() * earth_level_;
    Eigen::Vector3d g = m_inverse_ * true_rate_radps + bias_ + sigma_ * noise_.Normal3();
    if (walk_step_ > 0) bias_ += walk_step_ * noise_.Normal3();
    if (options_.gyro_units == GyroUnits::kCounts) {
      g = (Eigen::Vector3d::Constant(options_.gyro_counts_offset) +
           g * options_.gyro_counts_per_radps)
              .array()
              .round()
              .matrix();
    }
    return g;
  }

 private:
  const SimulateStaticOptions& options_;
  Eigen::Matrix3d m_inverse_;
  Eigen::Vector3d bias_;
  Eigen::Vector3d earth_level_ = Eigen::Vector3d::Zero();
  double walk_step_;
  double half_step_s_;
  double sigma_ = 0.0;
  Random noise_;
};

// Every sample of the session: the true state, the accelerometer (model,
// white noise, drift, digitisation) and the gyroscope when asked for.
void SampleStatic(const SimulateStaticOptions& options,
                  const internal::StaticPlan& plan,
                  const internal::StaticGeometry& geometry,
                  double gravity_mps2,
                  SimulatedSession& session) {
  const DevicePreset& device = options.device;
  const double rate = plan.rate_hz;
  const double sigma = device.noise_density_mps2_per_sqrt_hz * std::sqrt(rate / 2.0);
  session.noise_std_mps2 = Eigen::Vector3d::Constant(sigma);
  GyroSampler gyro(options, rate);
  Random noise(SplitMix64(options.seed ^ kNoiseStream));
  const Eigen::Vector3d up_level(0.0, 0.0, gravity_mps2);
  const double last_s = static_cast<double>(plan.total - 1) / rate;

  Recording& rec = session.recording;
  rec.units = options.units;
  rec.source = "<simulated>";
  rec.time_s.resize(plan.total);
  rec.accel.resize(plan.total);
  if (options.gyro) {
    rec.gyro_radps.resize(plan.total);
    rec.gyro_units = options.gyro_units;
    rec.gyro_log_units = options.gyro_units;
    session.true_rate_radps.resize(plan.total);
    session.gyro_noise_std_radps = gyro.sigma_radps();
  }
  for (std::size_t i = 0; i < plan.total; ++i) {
    const double t = static_cast<double>(i) / rate;
    rec.time_s[i] = t;
    Eigen::Quaterniond q_level_sensor;
    Eigen::Vector3d accel_level;
    geometry.StateAt(t, q_level_sensor, accel_level);
    // Specific force: what an ideal accelerometer senses, in the sensor frame.
    const Eigen::Vector3d f = q_level_sensor.conjugate() * (accel_level + up_level);
    Eigen::Vector3d y = device.truth.Forward(f) + sigma * noise.Normal3();
    y += options.bias_drift_mps2_per_s * (t - last_s);
    rec.accel[i] = internal::DigitiseAccel(y, device, options);
    if (options.gyro) {
      rec.gyro_radps[i] =
          gyro.Sample(geometry, t, q_level_sensor, session.true_rate_radps[i]);
    }
  }
}

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

namespace {

// Every number finite (NaN would pass the range checks below).
std::string CheckAllFinite(const SimulateStaticOptions& o) {
  const DevicePreset& dev = o.device;
  if (!o.bias_drift_mps2_per_s.allFinite()) return "bias_drift_mps2_per_s must be finite";
  for (const auto& [value, name] :
       {std::pair{dev.noise_density_mps2_per_sqrt_hz,
                  "device.noise_density_mps2_per_sqrt_hz"},
        std::pair{dev.rate_hz, "device.rate_hz"},
        std::pair{dev.range_mps2, "device.range_mps2"},
        std::pair{dev.resolution_mps2, "device.resolution_mps2"},
        std::pair{o.tilt_deg, "tilt_deg"},
        std::pair{o.dwell_s, "dwell_s"},
        std::pair{o.turn_s, "turn_s"},
        std::pair{o.initial_rest_s, "initial_rest_s"},
        std::pair{o.rate_hz, "rate_hz"},
        std::pair{o.shake_accel_mps2, "shake_accel_mps2"},
        std::pair{o.shake_rotation_deg, "shake_rotation_deg"},
        std::pair{o.gyro_noise_density_radps_per_sqrt_hz,
                  "gyro_noise_density_radps_per_sqrt_hz"},
        std::pair{dev.gyro_noise_density_radps_per_sqrt_hz,
                  "device.gyro_noise_density_radps_per_sqrt_hz"},
        std::pair{dev.gyro_bias_walk_radps_per_sqrt_s,
                  "device.gyro_bias_walk_radps_per_sqrt_s"},
        std::pair{o.gyro_counts_offset, "gyro_counts_offset"},
        std::pair{o.gyro_counts_per_radps, "gyro_counts_per_radps"},
        std::pair{o.counts_offset, "counts_offset"},
        std::pair{o.counts_per_mps2, "counts_per_mps2"}}) {
    if (std::string e = CheckFinite(value, name); !e.empty()) return e;
  }
  return "";
}

// The device's truth and noise: a model the solver could meet.
std::string CheckDevice(const DevicePreset& dev) {
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
  return "";
}

// The rate and the parts of the session, each at least two samples long.
std::string CheckTiming(const SimulateStaticOptions& o) {
  const DevicePreset& dev = o.device;
  if (o.rate_hz < 0)
    return fmt::format("rate_hz must be positive, or 0 for the device's (got {})",
                       o.rate_hz);
  const double rate = o.rate_hz > 0 ? o.rate_hz : dev.rate_hz;
  if (rate <= 0) return fmt::format("sample rate must be positive (got {} Hz)", rate);
  if (o.positions < 1)
    return fmt::format("positions must be at least 1 (got {})", o.positions);
  if (o.tilt_deg < 0 || o.tilt_deg > 90) {
    return fmt::format("tilt_deg must be between 0 and 90 degrees (got {})", o.tilt_deg);
  }
  if (o.dwell_s <= 0)
    return fmt::format("dwell_s must be positive (got {} s)", o.dwell_s);
  if (std::llround(o.dwell_s * rate) < 2) {
    return fmt::format("dwell_s = {} s gives fewer than 2 samples at {} Hz; hold longer",
                       o.dwell_s,
                       rate);
  }
  if (o.turn_s <= 0) return fmt::format("turn_s must be positive (got {} s)", o.turn_s);
  if (std::llround(o.turn_s * rate) < 2) {
    return fmt::format(
        "turn_s = {} s gives fewer than 2 samples at {} Hz", o.turn_s, rate);
  }
  if (o.initial_rest_s < 0) {
    return fmt::format("initial_rest_s must not be negative (got {} s)",
                       o.initial_rest_s);
  }
  return "";
}

// Shake and the gyroscope's model.
std::string CheckShakeAndGyro(const SimulateStaticOptions& o) {
  const DevicePreset& dev = o.device;
  if (o.shake_accel_mps2 < 0) return "shake_accel_mps2 must not be negative";
  if (o.shake_rotation_deg < 0) return "shake_rotation_deg must not be negative";
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
  if (o.gyro_counts_per_radps <= 0) {
    return fmt::format("gyro_counts_per_radps must be positive (got {})",
                       o.gyro_counts_per_radps);
  }
  if (o.earth_rate_latitude_deg && !(std::abs(*o.earth_rate_latitude_deg) <= 90.0)) {
    return "earth_rate_latitude_deg must be between -90 and 90";
  }
  if (o.counts_per_mps2 <= 0) {
    return fmt::format("counts_per_mps2 must be positive (got {})", o.counts_per_mps2);
  }
  return "";
}

}  // namespace

std::string SimulateStaticOptions::Validate() const {
  // In this order: the first problem is the one named.
  std::string problem = CheckAllFinite(*this);
  if (problem.empty()) problem = CheckDevice(device);
  if (problem.empty()) problem = CheckTiming(*this);
  if (problem.empty()) problem = CheckShakeAndGyro(*this);
  if (!problem.empty()) return problem;
  const double rate = rate_hz > 0 ? rate_hz : device.rate_hz;
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
    throw Error(ErrorKind::kOption, "invalid simulation options: " + problem);
  }
  if (!std::isfinite(gravity_mps2) || gravity_mps2 <= 0) {
    throw Error(
        ErrorKind::kOption,
        fmt::format("gravity must be positive and finite (got {} m/s²)", gravity_mps2));
  }
  const internal::StaticPlan plan = internal::PlanStaticSession(options);
  // Geometry first, all from one stream: directions, headings, shakes.
  const internal::StaticGeometry geometry = internal::DrawStaticGeometry(options, plan);
  SimulatedSession session;
  session.rate_hz = plan.rate_hz;
  session.directions = geometry.directions;
  session.still_ranges = geometry.still_ranges;
  SampleStatic(options, plan, geometry, gravity_mps2, session);

  session.truth = internal::StaticTruth(options, plan, gravity_mps2);
  double step = options.device.resolution_mps2;
  if (options.units == AccelUnits::kCounts)
    step = std::max(step, 1.0 / options.counts_per_mps2);
  session.quantisation_step_mps2 = step;
  Provenance provenance;
  provenance.input = "<simulated>";
  provenance.options = fmt::format(
      "simulate static: device {}, seed {}, positions {}, dwell {} s, turn {} s, rate {} "
      "Hz, "
      "noise density {} m/s²/√Hz, units {}",
      options.device.name.empty() ? "custom" : options.device.name,
      options.seed,
      options.positions,
      options.dwell_s,
      options.turn_s,
      plan.rate_hz,
      options.device.noise_density_mps2_per_sqrt_hz,
      ToString(options.units));
  session.truth.provenance = provenance;
  return session;
}

std::uint64_t TrialSeed(std::uint64_t base_seed, int trial) {
  return SplitMix64(SplitMix64(base_seed) + static_cast<std::uint64_t>(trial));
}

std::vector<SimulateStaticOptions> TrialOptions(const SimulateStaticOptions& options,
                                                int trials) {
  if (trials < 1) {
    throw Error(ErrorKind::kOption,
                fmt::format("trials must be at least 1 (got {})", trials));
  }
  if (const std::string problem = options.Validate(); !problem.empty()) {
    throw Error(ErrorKind::kOption, "invalid simulation options: " + problem);
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
