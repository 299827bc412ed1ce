// A synthetic verification walk: closed-form kinematics of a walker on a
// roughly rectangular loop, sampled by a simulated IMU and a GNSS receiver.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include "mpcal/error.h"
#include "mpcal/gravity.h"
#include "mpcal/simulate_walk.h"
#include "simulate/random.h"
#include "simulate/walk_steps.h"

namespace mpcal {
namespace {

constexpr double kPi = 3.14159265358979323846;

using Rng = internal::PortableRandom;

using internal::PhaseKind;
using State = internal::WalkState;
using Phase = internal::WalkPhase;

// Raised-cosine speed ramp from 0 to v over tau: distance, speed, acceleration.
void RampUp(double t, double v, double tau, double& s, double& ds, double& dds) {
  s = 0.5 * v * (t - tau / kPi * std::sin(kPi * t / tau));
  ds = 0.5 * v * (1.0 - std::cos(kPi * t / tau));
  dds = 0.5 * v * kPi / tau * std::sin(kPi * t / tau);
}

// x = A/w² (1 − cos wt): zero position and velocity after whole cycles.
void Bob(double t, double amplitude, double w, double& x, double& dx, double& ddx) {
  x = amplitude / (w * w) * (1.0 - std::cos(w * t));
  dx = amplitude / w * std::sin(w * t);
  ddx = amplitude * std::cos(w * t);
}

Eigen::Matrix3d Rz(double angle_rad) {
  return Eigen::AngleAxisd(angle_rad, Eigen::Vector3d::UnitZ()).toRotationMatrix();
}

// One side of the loop from `a` to `b`: ramp up, cruise, ramp down. The
// cruise holds whole sway cycles (two steps each), so that the bob ends where
// it started.
Phase Side(const SimulateWalkOptions& o,
           const Eigen::Vector3d& a,
           const Eigen::Vector3d& b,
           double heading_rad) {
  Phase p;
  p.kind = PhaseKind::kSide;
  p.from = a;
  const Eigen::Vector3d d = b - a;
  p.length_m = d.norm();
  p.along = d / p.length_m;
  p.heading_rad = heading_rad;
  p.cruise_s = (p.length_m - o.speed_mps * o.ramp_s) / o.speed_mps;
  const double sway_cycles = std::max(1.0, std::round(p.cruise_s * o.step_hz / 2.0));
  p.step_radps = 2.0 * kPi * 2.0 * sway_cycles / p.cruise_s;
  p.duration_s = 2.0 * o.ramp_s + p.cruise_s;
  return p;
}

// How the sensor sits on the walker: yaw relative to the walker, the
// mounting tilt, and the gyroscope's bias.
struct Mount {
  double yaw_offset_rad = 0.0;
  Eigen::Matrix3d R_tilt = Eigen::Matrix3d::Identity();
  Eigen::Vector3d gyro_bias_radps = Eigen::Vector3d::Zero();
  double fixed_heading_rad = 0.0;
  bool turns_with_walker = false;

  // The sensor's attitude at an instant: yaw with the walker when turning.
  Eigen::Matrix3d Attitude(const State& st) const {
    const double yaw =
        (turns_with_walker ? st.heading_rad : fixed_heading_rad) + yaw_offset_rad;
    return Eigen::Matrix3d(Rz(yaw) * R_tilt);
  }
};

Mount DrawMount(const SimulateWalkOptions& o, double fixed_heading_rad, Rng& shape) {
  Mount m;
  m.yaw_offset_rad = shape.Uniform(0.0, 2.0 * kPi);
  const double tilt_axis = shape.Uniform(0.0, 2.0 * kPi);
  m.R_tilt =
      Eigen::AngleAxisd(o.mount_tilt_deg * kPi / 180.0,
                        Eigen::Vector3d(std::cos(tilt_axis), std::sin(tilt_axis), 0.0))
          .toRotationMatrix();
  m.gyro_bias_radps = o.gyro_bias_std_radps * shape.Normal3();
  m.fixed_heading_rad = fixed_heading_rad;
  m.turns_with_walker = o.turn;
  return m;
}

// The IMU's readings over the whole timeline, and the true path.
void SampleImu(const SimulateWalkOptions& o,
               const std::vector<Phase>& phases,
               const Mount& mount,
               double gravity_mps2,
               Rng& noise,
               SimulatedWalk& walk) {
  const double total_s = phases.back().start_s + phases.back().duration_s;
  const double rate = o.rate_hz > 0.0 ? o.rate_hz : o.device.rate_hz;
  const double sigma = o.device.noise_density_mps2_per_sqrt_hz * std::sqrt(rate / 2.0);
  const double gyro_sigma =
      o.gyro_noise_density_radps_per_sqrt_hz * std::sqrt(rate / 2.0);
  const auto samples = static_cast<std::size_t>(std::floor(total_s * rate)) + 1;
  Recording& rec = walk.recording;
  rec.source = "<simulated>";
  rec.units = AccelUnits::kMps2;
  rec.time_s.reserve(samples);
  rec.accel.reserve(samples);
  walk.true_enu_m.reserve(samples);
  internal::WalkCursor cursor(phases, o);
  const Eigen::Vector3d g_up(0.0, 0.0, gravity_mps2);
  for (std::size_t k = 0; k < samples; ++k) {
    const double ts = static_cast<double>(k) / rate;
    const State st = cursor.At(ts);
    const Eigen::Matrix3d R = mount.Attitude(st);
    const Eigen::Vector3d f = R.transpose() * (st.acceleration + g_up);
    Eigen::Vector3d y = o.device.truth.Forward(f) + sigma * noise.Normal3();
    if (o.device.resolution_mps2 > 0.0) {
      y = (y / o.device.resolution_mps2).array().round() * o.device.resolution_mps2;
    }
    if (o.device.range_mps2 > 0.0) {
      y = y.cwiseMax(-o.device.range_mps2).cwiseMin(o.device.range_mps2);
    }
    rec.time_s.push_back(o.start_time_s + ts);
    rec.accel.push_back(y);
    if (o.turn) {
      rec.gyro_radps.push_back(R.transpose() *
                                   Eigen::Vector3d(0.0, 0.0, st.heading_rate_radps) +
                               mount.gyro_bias_radps + gyro_sigma * noise.Normal3());
    }
    walk.true_enu_m.push_back(st.position);
  }
  for (std::size_t k = 1; k < walk.true_enu_m.size(); ++k) {
    const Eigen::Vector3d d = walk.true_enu_m[k] - walk.true_enu_m[k - 1];
    walk.true_path_length_m += std::hypot(d.x(), d.y());
  }
}

// The GNSS reference: a little after the IMU starts, until it stops.
void SampleGnss(const SimulateWalkOptions& o,
                const std::vector<Phase>& phases,
                Rng& gnss_noise,
                SimulatedWalk& walk) {
  const double total_s = phases.back().start_s + phases.back().duration_s;
  internal::WalkCursor cursor(phases, o);
  const double gnss_dt = 1.0 / o.gnss_rate_hz;
  for (double tg = gnss_dt; tg <= total_s - gnss_dt; tg += gnss_dt) {
    const State st = cursor.At(tg);
    Eigen::Vector3d p = st.position;
    p.x() += o.gnss_noise_horizontal_m * gnss_noise.Normal();
    p.y() += o.gnss_noise_horizontal_m * gnss_noise.Normal();
    p.z() += o.gnss_noise_vertical_m * gnss_noise.Normal();
    PosEpoch e;
    // On the millisecond, as a receiver stamps its epochs.
    e.time_s = std::round((o.start_time_s + tg) * 1000.0) / 1000.0;
    e.position = EnuToGeodetic(o.origin, p);
    e.quality = 1;
    e.satellites = 18;
    e.std_neu_m = Eigen::Vector3d(
        o.gnss_noise_horizontal_m, o.gnss_noise_horizontal_m, o.gnss_noise_vertical_m);
    walk.gnss.push_back(e);
  }
}

}  // namespace

std::string SimulateWalkOptions::Validate() const {
  const auto positive = [](double v) { return std::isfinite(v) && v > 0.0; };
  const auto non_negative = [](double v) { return std::isfinite(v) && v >= 0.0; };
  if (!positive(length_m) || !positive(width_m))
    return "length_m and width_m must be positive";
  if (!positive(speed_mps) || speed_mps > 5.0) return "speed_mps must be in (0, 5] m/s";
  if (!positive(ramp_s)) return "ramp_s must be positive";
  if (speed_mps * ramp_s >= std::min(length_m, width_m) - 2.0 * corner_jitter_m) {
    return "the sides are too short for the speed ramps (length_m, width_m vs speed_mps "
           "× ramp_s)";
  }
  if (!positive(step_hz) || step_hz > 5.0) return "step_hz must be in (0, 5] Hz";
  if (!non_negative(bob_vertical_mps2) || !non_negative(bob_along_mps2) ||
      !non_negative(bob_sideways_mps2)) {
    return "bob amplitudes must be >= 0";
  }
  if (!non_negative(corner_stop_s)) return "corner_stop_s must be >= 0";
  if (!non_negative(rest_s)) return "rest_s must be >= 0";
  if (!non_negative(corner_jitter_m)) return "corner_jitter_m must be >= 0";
  if (!non_negative(mount_tilt_deg) || mount_tilt_deg > 45.0) {
    return "mount_tilt_deg must be in [0, 45] degrees";
  }
  if (!positive(turn_s)) return "turn_s must be positive";
  if (!non_negative(gyro_bias_std_radps)) return "gyro_bias_std_radps must be >= 0";
  if (!non_negative(gyro_noise_density_radps_per_sqrt_hz)) {
    return "gyro_noise_density_radps_per_sqrt_hz must be >= 0";
  }
  if (!positive(gnss_rate_hz) || gnss_rate_hz > 100.0)
    return "gnss_rate_hz must be in (0, 100]";
  if (!non_negative(gnss_noise_horizontal_m) || !non_negative(gnss_noise_vertical_m)) {
    return "GNSS noise must be >= 0";
  }
  if (!(std::abs(origin.latitude_deg) <= 89.0) ||
      !(std::abs(origin.longitude_deg) <= 180.0) || !std::isfinite(origin.height_m)) {
    return "origin must be a latitude within ±89°, a longitude within ±180°, a finite "
           "height";
  }
  if (!std::isfinite(start_time_s) || start_time_s < 0.0)
    return "start_time_s must be >= 0";
  if (!non_negative(rate_hz) || rate_hz > 10000.0) return "rate_hz must be in [0, 10000]";
  if (!non_negative(device.noise_density_mps2_per_sqrt_hz)) {
    return "device.noise_density_mps2_per_sqrt_hz must be >= 0";
  }
  if (!(rate_hz > 0.0) && !positive(device.rate_hz))
    return "device.rate_hz must be positive";
  return "";
}

namespace internal {

WalkState Evaluate(const WalkPhase& p, double t_s, const SimulateWalkOptions& o) {
  WalkState st;
  st.heading_rad = p.heading_rad;
  st.position = p.from;
  const double t = std::clamp(t_s - p.start_s, 0.0, p.duration_s);
  if (p.kind == PhaseKind::kTurn) {
    st.heading_rad =
        p.heading_rad + 0.5 * p.turn_rad * (1.0 - std::cos(kPi * t / p.duration_s));
    st.heading_rate_radps =
        0.5 * p.turn_rad * kPi / p.duration_s * std::sin(kPi * t / p.duration_s);
    return st;
  }
  if (p.kind == PhaseKind::kStill) return st;
  const double v = o.speed_mps;
  const double tau = o.ramp_s;
  const Eigen::Vector3d left(-p.along.y(), p.along.x(), 0.0);
  double s = 0.0, a = 0.0, lateral = 0.0, a_lat = 0.0, up = 0.0, a_up = 0.0;
  double ds = 0.0;
  if (t < tau) {
    RampUp(t, v, tau, s, ds, a);
  } else if (t < tau + p.cruise_s) {
    const double tc = t - tau;
    double bx = 0.0, bdx = 0.0, bddx = 0.0;
    Bob(tc, o.bob_along_mps2, p.step_radps, bx, bdx, bddx);
    s = 0.5 * v * tau + v * tc + bx;
    a = bddx;
    Bob(tc, o.bob_vertical_mps2, p.step_radps, up, bdx, a_up);
    Bob(tc, o.bob_sideways_mps2, 0.5 * p.step_radps, lateral, bdx, a_lat);
  } else {
    const double td = t - tau - p.cruise_s;
    double s_up = 0.0, a_ramp = 0.0;
    RampUp(td, v, tau, s_up, ds, a_ramp);
    // Mirror of the ramp up: speed falls from v to 0.
    s = 0.5 * v * tau + v * p.cruise_s + v * td - s_up;
    a = -a_ramp;
  }
  st.position = p.from + s * p.along + lateral * left + Eigen::Vector3d(0.0, 0.0, up);
  st.acceleration = a * p.along + a_lat * left + Eigen::Vector3d(0.0, 0.0, a_up);
  return st;
}

WalkState WalkCursor::At(double t_s) {
  while (phase_ + 1 < phases_.size() && t_s >= phases_[phase_ + 1].start_s) ++phase_;
  return Evaluate(phases_[phase_], t_s, options_);
}

std::vector<Eigen::Vector3d> LoopCorners(const SimulateWalkOptions& o,
                                         PortableRandom& shape) {
  const double azimuth = shape.Uniform(0.0, 2.0 * kPi);
  const Eigen::Vector3d u(std::cos(azimuth), std::sin(azimuth), 0.0);
  const Eigen::Vector3d v(-u.y(), u.x(), 0.0);
  std::vector<Eigen::Vector3d> corners = {Eigen::Vector3d::Zero(),
                                          o.length_m * u,
                                          o.length_m * u + o.width_m * v,
                                          o.width_m * v};
  for (std::size_t i = 1; i < corners.size(); ++i) {
    corners[i] +=
        Eigen::Vector3d(shape.Uniform(-1.0, 1.0), shape.Uniform(-1.0, 1.0), 0.0) *
        o.corner_jitter_m;
  }
  corners.push_back(corners.front());
  return corners;
}

std::vector<WalkPhase> WalkTimeline(const SimulateWalkOptions& o,
                                    const std::vector<Eigen::Vector3d>& corners) {
  std::vector<WalkPhase> phases;
  double t = 0.0;
  const auto add = [&](WalkPhase p) {
    p.start_s = t;
    t += p.duration_s;
    phases.push_back(p);
  };
  const auto heading_of = [&](std::size_t side) {
    const Eigen::Vector3d d = corners[side + 1] - corners[side];
    return std::atan2(d.y(), d.x());
  };
  WalkPhase rest;
  rest.duration_s = o.rest_s;
  rest.heading_rad = heading_of(0);
  add(rest);
  for (std::size_t side = 0; side < 4; ++side) {
    const WalkPhase p = Side(o, corners[side], corners[side + 1], heading_of(side));
    add(p);
    if (side == 3) break;
    WalkPhase stop;
    stop.kind = PhaseKind::kStill;
    stop.from = corners[side + 1];
    stop.heading_rad = p.heading_rad;
    if (o.turn) {
      const double still = 0.5 * (std::max(o.corner_stop_s, o.turn_s + 2.0) - o.turn_s);
      stop.duration_s = still;
      add(stop);
      WalkPhase turn = stop;
      turn.kind = PhaseKind::kTurn;
      turn.duration_s = o.turn_s;
      turn.turn_rad = std::remainder(heading_of(side + 1) - p.heading_rad, 2.0 * kPi);
      add(turn);
      stop.heading_rad = heading_of(side + 1);
      add(stop);
    } else {
      stop.duration_s = o.corner_stop_s;
      add(stop);
    }
  }
  WalkPhase end;
  end.kind = PhaseKind::kStill;
  end.from = corners.back();
  end.heading_rad = heading_of(3);
  end.duration_s = o.rest_s;
  add(end);
  return phases;
}

}  // namespace internal

SimulatedWalk SimulateWalk(const SimulateWalkOptions& o, double gravity_mps2) {
  if (const std::string p = o.Validate(); !p.empty()) {
    throw Error(ErrorKind::kOption, "simulate walk: " + p);
  }
  if (!IsPlausibleGravity(gravity_mps2)) {
    throw Error(ErrorKind::kOption,
                fmt::format("simulate walk: gravity {} m/s2 is not a gravity magnitude",
                            gravity_mps2));
  }
  // Separate streams, so that changing the noise leaves the loop alone.
  Rng shape(o.seed);
  Rng noise(o.seed ^ 0x9E3779B97F4A7C15ULL);
  Rng gnss_noise(o.seed ^ 0xC2B2AE3D27D4EB4FULL);
  const std::vector<Eigen::Vector3d> corners = internal::LoopCorners(o, shape);
  const std::vector<Phase> phases = internal::WalkTimeline(o, corners);
  const Mount mount = DrawMount(o, phases.front().heading_rad, shape);

  SimulatedWalk walk;
  SampleImu(o, phases, mount, gravity_mps2, noise, walk);
  SampleGnss(o, phases, gnss_noise, walk);
  walk.truth.model_kind = ModelKind::kShinElSheimy9;
  walk.truth.gravity_mps2 = gravity_mps2;
  walk.truth.input_units = AccelUnits::kMps2;
  walk.truth.mps2_per_unit = 1.0;
  walk.truth.model = o.device.truth;
  return walk;
}

}  // namespace mpcal
