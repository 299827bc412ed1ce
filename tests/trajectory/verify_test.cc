// The field verification end to end: the issue's "done when" claims on the
// project's simulated walks, on walks of an independent generator written
// here, and on the real RTKLIB walk.
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "mpcal/error.h"
#include "mpcal/gnss.h"
#include "mpcal/log_reader.h"
#include "mpcal/simulate_walk.h"
#include "mpcal/verification_file.h"
#include "mpcal/verify.h"
#include "test_util.h"

namespace mpcal {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

// "A small fraction": the corrected start-to-end distance at most this share
// of the raw one. On the runs below the measured share is 0.2-11 %; what is
// left after correction is the mounting tilt (z-up) or the tilt random walk
// of the gyroscope noise (turning), not the accelerometer.
constexpr double kSmallFraction = 0.25;

struct WalkRun {
  VerifyResult result;
  SimulatedWalk walk;
};

WalkRun VerifyProjectWalk(const std::string& preset,
                          bool turn,
                          MountMode mount,
                          std::uint64_t seed) {
  SimulateWalkOptions o;
  o.device = FindPreset(preset);
  o.seed = seed;
  o.turn = turn;
  WalkRun run{{}, SimulateWalk(o)};
  const GnssTrack ref = ParseGnss(FormatRtklibPos(run.walk.gnss), "walk.pos");
  VerifyOptions v;
  v.integrate.mount = mount;
  run.result = Verify(run.walk.recording, ref, run.walk.truth, v);
  return run;
}

class ProjectWalk : public ::testing::TestWithParam<std::string> {};

TEST_P(ProjectWalk, TurningWalkCorrectedClosesMuchBetterThanRaw) {
  const WalkRun run = VerifyProjectWalk(GetParam(), /*turn=*/true, MountMode::kLevel, 11);
  const VerifyResult& r = run.result;
  ASSERT_TRUE(r.corrected.has_value());
  EXPECT_TRUE(r.gyro_used);
  EXPECT_LT(r.corrected->start_end_distance_m,
            kSmallFraction * r.raw.start_end_distance_m)
      << "raw " << r.raw.start_end_distance_m << " corrected "
      << r.corrected->start_end_distance_m;
  EXPECT_LT(r.corrected->horizontal_rms_m, r.raw.horizontal_rms_m);
  // The reference closes to its noise; the walk is ~128 m.
  EXPECT_LT(r.reference.start_end_distance_m, 0.1);
  EXPECT_NEAR(r.reference.path_length_m,
              run.walk.true_path_length_m,
              0.03 * run.walk.true_path_length_m);
  EXPECT_EQ(r.time.method, TimeAlignMode::kCommonClock);
}

TEST_P(ProjectWalk, NonTurningWalkWithStatedMountShowsTheBias) {
  const WalkRun run = VerifyProjectWalk(GetParam(), /*turn=*/false, MountMode::kZUp, 12);
  const VerifyResult& r = run.result;
  ASSERT_TRUE(r.corrected.has_value());
  EXPECT_FALSE(r.gyro_used);
  EXPECT_LT(r.corrected->start_end_distance_m,
            kSmallFraction * r.raw.start_end_distance_m)
      << "raw " << r.raw.start_end_distance_m << " corrected "
      << r.corrected->start_end_distance_m;
  EXPECT_LT(r.corrected->horizontal_rms_m, r.raw.horizontal_rms_m);
}

TEST_P(ProjectWalk, LevellingAbsorbsTheBiasWhenTheSensorNeverRotates) {
  // The same walk levelled: raw and corrected both close to within a couple
  // of metres (noise, quantisation), against hundreds with z-up.
  constexpr double kLevelledClosureM = 2.0;
  const WalkRun run =
      VerifyProjectWalk(GetParam(), /*turn=*/false, MountMode::kLevel, 12);
  const VerifyResult& r = run.result;
  EXPECT_LT(r.raw.start_end_distance_m, kLevelledClosureM);
  EXPECT_LT(r.corrected->start_end_distance_m, kLevelledClosureM);
  EXPECT_LT(std::abs(r.raw.horizontal_rms_m - r.corrected->horizontal_rms_m),
            kLevelledClosureM);
}

INSTANTIATE_TEST_SUITE_P(Presets, ProjectWalk, ::testing::ValuesIn(PresetNames()));

// ---------------------------------------------------------------------------
// An independent walk generator: a figure-eight of two circles walked with a
// minimum-jerk speed profile and a two-harmonic step bob, accelerations and
// rates by numerical differentiation of the pose, readings in g, the
// reference as an e,n,u CSV on another clock. Nothing is shared with
// src/simulate but the error model's Forward.
struct FigureEightOptions {
  bool turn = false;       // the sensor yaws with the walker
  double tilt_deg = 0.05;  // mounting tilt
  std::uint64_t seed = 1;
};

struct FigureEight {
  Recording imu;
  GnssTrack reference;
  Calibration truth;
};

FigureEight MakeFigureEight(const FigureEightOptions& opt) {
  constexpr double kRadius = 8.0, kSpeed = 1.3, kRamp = 1.5, kRest = 15.0, kStop = 4.0;
  constexpr double kGravity = 9.79, kRate = 200.0, kStepHz = 1.9;
  const double leg = 2.0 * M_PI * kRadius;
  const double cruise = (leg - kSpeed * kRamp) / kSpeed;
  const double leg_s = 2.0 * kRamp + cruise;
  const double total = 2.0 * kRest + 2.0 * leg_s + kStop;
  // Distance along a leg and the speed fraction at time tl into it.
  const auto along = [&](double tl, double& frac) {
    const auto ramp = [&](double tau) {  // ∫ of 10τ³−15τ⁴+6τ⁵
      return kSpeed * kRamp *
             (2.5 * std::pow(tau, 4) - 3 * std::pow(tau, 5) + std::pow(tau, 6));
    };
    const auto speed = [](double tau) {
      return 10 * std::pow(tau, 3) - 15 * std::pow(tau, 4) + 6 * std::pow(tau, 5);
    };
    if (tl <= 0.0) return frac = 0.0;
    if (tl < kRamp) {
      frac = speed(tl / kRamp);
      return ramp(tl / kRamp);
    }
    if (tl < kRamp + cruise) {
      frac = 1.0;
      return 0.5 * kSpeed * kRamp + kSpeed * (tl - kRamp);
    }
    if (tl < leg_s) {
      const double td = leg_s - tl;
      frac = speed(td / kRamp);
      return leg - ramp(td / kRamp);
    }
    frac = 0.0;
    return leg;
  };
  // Pose: position (m, ENU) and walker heading (rad).
  const auto pose = [&](double t, double& heading) {
    double frac = 0.0;
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    const double t1 = t - kRest;
    const double t2 = t - kRest - leg_s - kStop;
    double sway_sign = 1.0;
    if (t2 > 0.0) {  // second circle, clockwise
      const double phi = along(t2, frac) / kRadius;
      p = {kRadius * std::sin(phi), -kRadius * (1 - std::cos(phi)), 0.0};
      heading = -phi;
      sway_sign = -1.0;
    } else {  // first circle, counter-clockwise
      const double phi = along(t1, frac) / kRadius;
      p = {kRadius * std::sin(phi), kRadius * (1 - std::cos(phi)), 0.0};
      heading = phi;
    }
    const double w = 2 * M_PI * kStepHz;
    const Eigen::Vector3d left(-std::sin(heading), std::cos(heading), 0.0);
    p.z() += frac * (0.035 * (1 - std::cos(w * t)) + 0.01 * std::sin(2 * w * t));
    p += sway_sign * frac * 0.025 * std::sin(0.5 * w * t) * left;
    return p;
  };
  const double tilt_axis = 0.7;
  const Eigen::Matrix3d R_tilt =
      Eigen::AngleAxisd(opt.tilt_deg * M_PI / 180.0,
                        Eigen::Vector3d(std::cos(tilt_axis), std::sin(tilt_axis), 0))
          .toRotationMatrix();
  const auto attitude = [&](double t) {
    double heading = 0.0;
    pose(t, heading);
    const double yaw = (opt.turn ? heading : 0.0) + 2.0;
    return Eigen::Matrix3d(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * R_tilt);
  };

  FigureEight out;
  ErrorModel& m = out.truth.model;
  m.bias_mps2 = {0.25, -0.18, 0.12};
  m.scale_factor_error = {1.5e-3, -1e-3, 2e-3};
  m.theta_yz_rad = 5e-4;
  m.theta_zx_rad = -3e-4;
  m.theta_zy_rad = 8e-4;
  out.truth.gravity_mps2 = kGravity;
  out.truth.input_units = AccelUnits::kG;
  out.truth.mps2_per_unit = kStandardGravityMps2;

  std::mt19937_64 rng(opt.seed);
  std::normal_distribution<double> accel_noise(0.0, 0.02), gyro_noise(0.0, 1e-3),
      gnss_noise(0.0, 0.015);
  constexpr double h = 1e-3;  // differentiation step (s)
  out.imu.units = AccelUnits::kG;
  out.imu.source = "<figure-eight>";
  for (double t = 0.0; t < total; t += 1.0 / kRate) {
    double hd = 0.0;
    const Eigen::Vector3d a =
        (pose(t + h, hd) - 2.0 * pose(t, hd) + pose(t - h, hd)) / (h * h);
    const Eigen::Matrix3d R = attitude(t);
    const Eigen::Vector3d f = R.transpose() * (a + Eigen::Vector3d(0, 0, kGravity));
    const Eigen::Vector3d noise(accel_noise(rng), accel_noise(rng), accel_noise(rng));
    out.imu.time_s.push_back(t);
    out.imu.accel.push_back((m.Forward(f) + noise) / kStandardGravityMps2);
    if (opt.turn) {
      const Eigen::Matrix3d dR =
          R.transpose() * (attitude(t + h) - attitude(t - h)) / (2 * h);
      out.imu.gyro_radps.emplace_back(dR(2, 1) + gyro_noise(rng),
                                      dR(0, 2) + gyro_noise(rng),
                                      dR(1, 0) + gyro_noise(rng));
    }
  }
  // The reference: 10 Hz on a clock 500 s ahead, as an e,n,u CSV.
  std::string csv = "t,e,n,u\n";
  for (double t = 0.05; t < total; t += 0.1) {
    double hd = 0.0;
    const Eigen::Vector3d p = pose(t, hd);
    csv += fmt::format("{:.3f},{:.4f},{:.4f},{:.4f}\n",
                       t + 500.0,
                       p.x() + gnss_noise(rng),
                       p.y() + gnss_noise(rng),
                       p.z() + gnss_noise(rng));
  }
  out.reference = ParseGnss(csv, "figure-eight.csv");
  return out;
}

VerifyResult VerifyFigureEight(const FigureEight& w, MountMode mount) {
  VerifyOptions v;
  v.integrate.mount = mount;
  v.integrate.gravity_mps2 = w.truth.gravity_mps2;
  v.time_align = TimeAlignMode::kMotionStart;
  return Verify(w.imu, w.reference, w.truth, v);
}

TEST(IndependentWalk, TurningFigureEightCorrectedClosesMuchBetterThanRaw) {
  FigureEightOptions o;
  o.turn = true;
  o.tilt_deg = 3.0;  // levelling finds it
  const FigureEight w = MakeFigureEight(o);
  const VerifyResult r = VerifyFigureEight(w, MountMode::kLevel);
  // Motion alignment finds the 500 s between the clocks.
  EXPECT_NEAR(r.time.offset_s, 500.0, 0.05);
  EXPECT_TRUE(r.gyro_used);
  EXPECT_LT(r.corrected->start_end_distance_m,
            kSmallFraction * r.raw.start_end_distance_m)
      << "raw " << r.raw.start_end_distance_m << " corrected "
      << r.corrected->start_end_distance_m;
  EXPECT_LT(r.corrected->horizontal_rms_m, r.raw.horizontal_rms_m);
}

TEST(IndependentWalk, NonTurningFigureEightWithStatedMountShowsTheBias) {
  const FigureEight w = MakeFigureEight({});
  const VerifyResult r = VerifyFigureEight(w, MountMode::kZUp);
  EXPECT_NEAR(r.time.offset_s, 500.0, 0.05);
  EXPECT_LT(r.corrected->start_end_distance_m,
            kSmallFraction * r.raw.start_end_distance_m)
      << "raw " << r.raw.start_end_distance_m << " corrected "
      << r.corrected->start_end_distance_m;
  EXPECT_LT(r.corrected->horizontal_rms_m, r.raw.horizontal_rms_m);
}

// ---------------------------------------------------------------------------

TEST(VerifyRealWalk, RtklibWalkRunsEndToEnd) {
  LogOptions log;
  log.columns = "t=0,ax=1,ay=2,az=3,gx=4,gy=5,gz=6";
  log.units = AccelUnits::kG;
  const Recording imu =
      ReadLog(testing::RealDataPath("rtklib-walk/imu_1730_sf.csv"), log);
  const GnssTrack ref = ReadGnss(testing::RealDataPath("rtklib-walk/gnss_1730_sf.pos"));
  VerifyOptions v;
  v.integrate.gravity_mps2 = 9.7968;  // normal gravity at 40.1° N, 1601 m
  const VerifyResult r = Verify(imu, ref, std::nullopt, v);
  EXPECT_EQ(r.time.method, TimeAlignMode::kCommonClock);
  // Its clock is GPS time, like the .pos: the start of motion agrees.
  ASSERT_TRUE(r.time.motion_offset_s.has_value());
  EXPECT_NEAR(*r.time.motion_offset_s, 0.0, 0.5);
  EXPECT_TRUE(r.gyro_used);
  // The data README: 129 m around a loop closing to 0.2 m.
  EXPECT_NEAR(r.reference.path_length_m, 129.0, 2.0);
  EXPECT_NEAR(r.reference.start_end_distance_m, 0.2, 0.05);
  EXPECT_TRUE(std::isfinite(r.raw.start_end_distance_m));
  EXPECT_GT(r.raw.path_length_m, 0.0);
  EXPECT_FALSE(r.corrected.has_value());
  EXPECT_FALSE(r.raw_path.empty());
}

// ---------------------------------------------------------------------------

SimulatedWalk SmallWalk() {
  SimulateWalkOptions o;
  o.device = FindPreset("mti-g");
  o.length_m = 12.0;
  o.width_m = 8.0;
  o.rest_s = 5.0;
  o.rate_hz = 100.0;
  return SimulateWalk(o);
}

TEST(Verify, LogsThatDoNotOverlapAreAClearError) {
  const SimulatedWalk w = SmallWalk();
  const GnssTrack ref = ParseGnss(FormatRtklibPos(w.gnss), "walk.pos");
  Recording imu = w.recording;
  for (double& t : imu.time_s) t -= 3600.0;
  VerifyOptions v;
  v.time_align = TimeAlignMode::kCommonClock;
  EXPECT_THAT([&] { Verify(imu, ref, std::nullopt, v); },
              ThrowsMessage<Error>(HasSubstr("do not overlap in time")));
  // Auto falls back to the start of motion, which finds the hour.
  v.time_align = TimeAlignMode::kAuto;
  const VerifyResult r = Verify(imu, ref, std::nullopt, v);
  EXPECT_EQ(r.time.method, TimeAlignMode::kMotionStart);
  EXPECT_NEAR(r.time.offset_s, 3600.0, 0.05);
  // The user's offset.
  v.time_align = TimeAlignMode::kOffset;
  v.time_offset_s = 3600.0;
  EXPECT_DOUBLE_EQ(Verify(imu, ref, std::nullopt, v).time.offset_s, 3600.0);
}

TEST(Verify, WrongUnitsAndInputsAreErrors) {
  const SimulatedWalk w = SmallWalk();
  const GnssTrack ref = ParseGnss(FormatRtklibPos(w.gnss), "walk.pos");
  Recording counts = w.recording;
  counts.units = AccelUnits::kCounts;
  EXPECT_THAT([&] { Verify(counts, ref, std::nullopt, {}); },
              ThrowsMessage<Error>(HasSubstr("raw counts")));
  Calibration in_g = w.truth;
  in_g.input_units = AccelUnits::kG;
  // The advice: read the log in g (the command says "--units g").
  try {
    Verify(w.recording, ref, in_g, {});
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kUnits);
    ASSERT_EQ(e.advice().settings.size(), 1u);
    EXPECT_EQ(e.advice().settings[0].option, Option::kLogUnits);
    EXPECT_EQ(e.advice().settings[0].value, "g");
  }
  GnssTrack one = ref;
  one.time_s.resize(1);
  one.enu_m.resize(1);
  one.quality.resize(1);
  EXPECT_THAT([&] { Verify(w.recording, one, std::nullopt, {}); },
              ThrowsMessage<Error>(HasSubstr("the reference has 1 epoch; a walk")));
  // A reference that never leaves its start has no heading.
  GnssTrack still = ref;
  for (Eigen::Vector3d& p : still.enu_m) p.setZero();
  EXPECT_THAT([&] { Verify(w.recording, still, std::nullopt, {}); },
              ThrowsMessage<Error>(HasSubstr("initial heading")));
  VerifyOptions bad;
  bad.heading_distance_m = -1.0;
  EXPECT_THAT([&] { Verify(w.recording, ref, std::nullopt, bad); },
              ThrowsMessage<Error>(HasSubstr("heading_distance_m")));
}

// At rest throughout, the zero-velocity updates hold the integration at its
// start: 0 m from start to end is no verdict on the calibration.
TEST(Verify, AnImuThatNeverMovesVerifiesNothing) {
  const SimulatedWalk w = SmallWalk();
  const GnssTrack ref = ParseGnss(FormatRtklibPos(w.gnss), "walk.pos");
  Recording still = w.recording;
  still.source = "still.csv";
  // Lying flat with the noise the walk's sensor has (a reading of the rest).
  std::mt19937_64 rng(3);
  std::normal_distribution<double> noise(0.0, 0.003);
  for (Eigen::Vector3d& a : still.accel) {
    a = Eigen::Vector3d(noise(rng), noise(rng), 9.80665 + noise(rng));
  }
  for (Eigen::Vector3d& g : still.gyro_radps) g = Eigen::Vector3d(noise(rng), 0.0, 0.0);
  const double span_s = still.time_s.back() - still.time_s.front();
  EXPECT_THAT([&] { Verify(still, ref, w.truth, {}); },
              ThrowsMessage<Error>(HasSubstr(
                  fmt::format("still.csv: the IMU never moves: the still test finds it "
                              "at rest over all {:.1f} s of the log",
                              span_s))));
  // The walk itself moves.
  EXPECT_GT(Verify(w.recording, ref, w.truth, {}).raw.path_length_m, 10.0);
}

TEST(Verify, ResultJsonHasTheIssuesKeys) {
  const SimulatedWalk w = SmallWalk();
  const GnssTrack ref = ParseGnss(FormatRtklibPos(w.gnss), "walk.pos");
  const VerifyResult with = Verify(w.recording, ref, w.truth, {});
  const nlohmann::json j = nlohmann::json::parse(VerificationToJson(with));
  EXPECT_EQ(j["format"], "mpcal.verification/1");
  for (const char* key : {"path_length_m", "start_end_distance_m"}) {
    EXPECT_TRUE(j["reference"][key].is_number()) << key;
  }
  for (const char* part : {"raw", "corrected"}) {
    for (const char* key : {"start_end_distance_m",
                            "horizontal_rms_m",
                            "horizontal_max_m",
                            "path_length_m"}) {
      EXPECT_TRUE(j[part][key].is_number()) << part << "." << key;
    }
  }
  EXPECT_DOUBLE_EQ(j["raw"]["horizontal_rms_m"].get<double>(), with.raw.horizontal_rms_m);
  const VerifyResult without = Verify(w.recording, ref, std::nullopt, {});
  EXPECT_FALSE(nlohmann::json::parse(VerificationToJson(without)).contains("corrected"));
  EXPECT_FALSE(j.contains("trajectories"));
  // The trajectory CSVs, when written, are named for `mpcal report`.
  const nlohmann::json named = nlohmann::json::parse(
      VerificationToJson(with, {{"reference", "w-reference.csv"}, {"raw", "w-raw.csv"}}));
  EXPECT_EQ(named["trajectories"],
            nlohmann::json({{"reference", "w-reference.csv"}, {"raw", "w-raw.csv"}}));
}

TEST(Verify, TrajectoryCsvHasAHeaderAndARowPerPoint) {
  TimedPath p;
  p.time_s = {1.0, 2.0};
  p.position_m = {Eigen::Vector3d(1, 2, 3), Eigen::Vector3d(4, 5, 6)};
  EXPECT_EQ(PathToCsv(p),
            "t_s,e_m,n_m,u_m\n1.0000,1.0000,2.0000,3.0000\n"
            "2.0000,4.0000,5.0000,6.0000\n");
  EXPECT_THAT(PathToCsv(p, {1, 2}), HasSubstr("t_s,e_m,n_m,u_m,q\n"));
}

TEST(VerifyOptions, DefaultsAreValidAndModesRoundTrip) {
  EXPECT_EQ(VerifyOptions{}.Validate(), "");
  for (const TimeAlignMode m : {TimeAlignMode::kAuto,
                                TimeAlignMode::kCommonClock,
                                TimeAlignMode::kOffset,
                                TimeAlignMode::kMotionStart}) {
    EXPECT_EQ(ParseTimeAlignMode(ToString(m)), m);
  }
}

}  // namespace
}  // namespace mpcal
