// Still test, integration, alignment and metrics on hand-made signals.
#include <cmath>
#include <random>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mpcal/error.h"
#include "mpcal/trajectory.h"

namespace mpcal {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

constexpr double kG = 9.80665;
constexpr double kRateHz = 100.0;
constexpr double kDt = 1.0 / kRateHz;

// A signal: rest, then motion, then rest, in the sensor frame (z up).
struct Signal {
  std::vector<double> t;
  std::vector<Eigen::Vector3d> f;
  std::vector<Eigen::Vector3d> w;
};

Signal RestMoveRest(double rest_s, double move_s, double noise_mps2, unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> n(0.0, noise_mps2);
  Signal s;
  const int samples = static_cast<int>((2 * rest_s + move_s) * kRateHz);
  for (int k = 0; k < samples; ++k) {
    const double t = k * kDt;
    Eigen::Vector3d f(0.0, 0.0, kG);
    if (t >= rest_s && t < rest_s + move_s) {
      f += Eigen::Vector3d(
          std::sin(2 * M_PI * 1.8 * t), 0.0, 1.5 * std::cos(2 * M_PI * 1.8 * t));
    }
    s.t.push_back(t);
    s.f.push_back(f + Eigen::Vector3d(n(rng), n(rng), n(rng)));
  }
  return s;
}

TEST(StillOptions, DefaultsAreValid) {
  EXPECT_EQ(StillOptions{}.Validate(), "");
  EXPECT_EQ(IntegrateOptions{}.Validate(), "");
  StillOptions o;
  o.window_s = 0.0;
  EXPECT_THAT(o.Validate(), HasSubstr("window_s"));
  IntegrateOptions i;
  i.gravity_mps2 = 1.0;
  EXPECT_THAT(i.Validate(), HasSubstr("gravity_mps2"));
}

TEST(DetectStill, FindsTheRestsAroundMotion) {
  const Signal s = RestMoveRest(5.0, 3.0, 0.01, 1);
  const StillResult r = DetectStill(s.t, s.f, {}, StillOptions{});
  ASSERT_EQ(r.intervals.size(), 2u);
  // The centred window (0.5 s) blurs each edge by at most half of it.
  constexpr double kEdgeTolS = 0.25 + kDt;
  EXPECT_EQ(r.intervals[0].first, 0u);
  EXPECT_NEAR(s.t[r.intervals[0].second], 5.0, kEdgeTolS);
  EXPECT_NEAR(s.t[r.intervals[1].first], 8.0, kEdgeTolS);
  EXPECT_EQ(r.intervals[1].second, s.t.size());
  EXPECT_EQ(r.initial_rest_end, r.intervals[0].second);
  EXPECT_EQ(r.accel_std_mps2.size(), s.t.size());
}

TEST(DetectStill, ATurnOnTheSpotIsNotStillWhenThereIsAGyroscope) {
  Signal s = RestMoveRest(5.0, 0.0, 0.01, 2);
  // Rotation about z between 3 and 5 s: the accelerometer does not see it.
  for (std::size_t k = 0; k < s.t.size(); ++k) {
    const double rate = s.t[k] >= 3.0 && s.t[k] < 5.0 ? 0.8 : 0.0;
    s.w.emplace_back(0.001, -0.002, rate);
  }
  EXPECT_EQ(DetectStill(s.t, s.f, {}, StillOptions{}).intervals.size(), 1u);
  const StillResult r = DetectStill(s.t, s.f, s.w, StillOptions{});
  ASSERT_EQ(r.intervals.size(), 2u);
  EXPECT_GT(r.gyro_threshold_radps, 0.0);
  EXPECT_NEAR(s.t[r.intervals[0].second], 3.0, 0.25 + kDt);
  EXPECT_NEAR(s.t[r.intervals[1].first], 5.0, 0.25 + kDt);
}

TEST(DetectStill, RejectsTooShortAndMismatchedInput) {
  const std::vector<double> t = {0.0, 0.01};
  const std::vector<Eigen::Vector3d> f(2, Eigen::Vector3d(0, 0, kG));
  EXPECT_THROW(DetectStill(t, f, {}, StillOptions{}), Error);
  const Signal s = RestMoveRest(1.0, 1.0, 0.01, 3);
  const std::vector<Eigen::Vector3d> short_f(s.f.begin(), s.f.end() - 1);
  EXPECT_THAT([&] { DetectStill(s.t, short_f, {}, StillOptions{}); },
              ThrowsMessage<Error>(HasSubstr("different lengths")));
}

// Constant forward acceleration after a rest, with a tilted sensor:
// levelling must take the tilt out exactly, and the trapezoidal rule is
// exact for a quadratic path.
TEST(IntegrateTrajectory, LevelledConstantAccelerationGivesAQuadraticPath) {
  const Eigen::Matrix3d R_nav_sensor =
      Eigen::AngleAxisd(0.2, Eigen::Vector3d(1, 1, 0).normalized()).toRotationMatrix();
  Signal s;
  const double accel = 0.5;
  const double rest_s = 3.0;
  for (int k = 0; k <= 1300; ++k) {
    const double t = k * kDt;
    const Eigen::Vector3d a_nav(t > rest_s ? accel : 0.0, 0.0, 0.0);
    s.t.push_back(t);
    s.f.push_back(R_nav_sensor.transpose() * (a_nav + Eigen::Vector3d(0, 0, kG)));
  }
  StillResult still;
  still.still.assign(s.t.size(), false);
  still.initial_rest_end = static_cast<std::size_t>(rest_s * kRateHz);
  std::fill(still.still.begin(), still.still.begin() + 300, true);
  IntegrateOptions o;
  o.gravity_mps2 = kG;
  const IntegrationResult r = IntegrateTrajectory(s.t, s.f, {}, still, o);
  EXPECT_NEAR(r.initial_tilt_rad, 0.2, 1e-12);
  // The trapezoidal rule sees the step in acceleration as a ramp over the
  // first sample, i.e. a step half a sample later; beyond that it is exact
  // up to accel·dt²/24.
  constexpr double kTolM = 0.5 * kDt * kDt;
  const double t_move = s.t.back() - rest_s;
  const double t_eff = t_move - 0.5 * kDt;
  const Eigen::Vector3d p = r.path.position_m.back();
  EXPECT_NEAR(std::hypot(p.x(), p.y()), 0.5 * accel * t_eff * t_eff, kTolM);
  EXPECT_NEAR(p.z(), 0.0, 1e-9);
  EXPECT_NEAR(r.velocity_mps.back().norm(), accel * t_move, accel * kDt);
}

TEST(IntegrateTrajectory, ZUpShowsABiasThatLevellingAbsorbs) {
  // A sensor at rest, z up, with a horizontal bias of 0.1 m/s².
  Signal s;
  for (int k = 0; k <= 1000; ++k) {
    s.t.push_back(k * kDt);
    s.f.emplace_back(0.1, 0.0, kG);
  }
  StillResult still;
  still.still.assign(s.t.size(), false);
  still.initial_rest_end = 200;
  std::fill(still.still.begin(), still.still.begin() + 200, true);
  IntegrateOptions level;
  IntegrateOptions zup;
  zup.mount = MountMode::kZUp;
  zup.zero_velocity_updates = false;
  const double t_end = s.t.back();
  const IntegrationResult a = IntegrateTrajectory(s.t, s.f, {}, still, level);
  const IntegrationResult b = IntegrateTrajectory(s.t, s.f, {}, still, zup);
  EXPECT_NEAR(a.path.position_m.back().head<2>().norm(), 0.0, 1e-9);
  EXPECT_NEAR(b.path.position_m.back().x(), 0.5 * 0.1 * t_end * t_end, 1e-6);
}

TEST(IntegrateTrajectory, GyroscopeCarriesTheBiasIntoTheHorizontalAfterATurn) {
  // Levelled at rest with bias b along x; then the sensor turns 180° about z
  // on the spot: the levelling's tilt now adds to the bias instead of
  // cancelling it, 2b horizontally.
  const double b = 0.05;
  Signal s;
  const double turn_start = 2.0, turn_s = 1.0;
  for (int k = 0; k <= 600; ++k) {
    const double t = k * kDt;
    const bool turning = t >= turn_start && t < turn_start + turn_s;
    s.t.push_back(t);
    s.w.emplace_back(0.0, 0.0, turning ? M_PI / turn_s : 0.0);
  }
  // Specific force in the sensor frame: gravity seen from the turned sensor,
  // plus the bias in the sensor frame.
  double yaw = 0.0;
  for (std::size_t k = 0; k < s.t.size(); ++k) {
    if (k > 0) yaw += 0.5 * (s.w[k - 1].z() + s.w[k].z()) * kDt;
    const Eigen::Matrix3d R =
        Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    s.f.push_back(R.transpose() * Eigen::Vector3d(0, 0, kG) + Eigen::Vector3d(b, 0, 0));
  }
  StillResult still;
  still.still.assign(s.t.size(), false);
  still.initial_rest_end = 200;
  std::fill(still.still.begin(), still.still.begin() + 200, true);
  IntegrateOptions o;
  o.zero_velocity_updates = false;
  const IntegrationResult r = IntegrateTrajectory(s.t, s.f, s.w, still, o);
  EXPECT_TRUE(r.gyro_used);
  // The error is b·(R(ψ)x − x): during the uniform turn it averages to
  // b·(−1, 2/π), after it is 2b along −x.
  const double after = s.t.back() - (turn_start + turn_s);
  const Eigen::Vector3d v = r.velocity_mps.back();
  const Eigen::Vector2d expected(-b * (turn_s + 2.0 * after), b * turn_s * 2.0 / M_PI);
  EXPECT_NEAR((v.head<2>() - expected).norm(), 0.0, 0.01 * expected.norm())
      << v.transpose();
}

TEST(IntegrateTrajectory, LevellingWithoutAnInitialRestIsAnError) {
  const Signal s = RestMoveRest(0.0, 5.0, 0.01, 4);
  StillResult still;
  still.still.assign(s.t.size(), false);
  // The advice: state the mount as z-up (the command says "--mount z-up").
  try {
    IntegrateTrajectory(s.t, s.f, {}, still, IntegrateOptions{});
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("record a rest before walking"));
    ASSERT_EQ(e.advice().settings.size(), 1u);
    EXPECT_EQ(e.advice().settings[0].option, Option::kMount);
    EXPECT_EQ(e.advice().settings[0].value, "z-up");
  }
  IntegrateOptions zup;
  zup.mount = MountMode::kZUp;
  EXPECT_NO_THROW(IntegrateTrajectory(s.t, s.f, {}, still, zup));
}

TEST(IntegrateTrajectory, ZeroVelocityUpdatesStopTheDrift) {
  // Bias along x, z-up: walking 2 s, stopping 2 s, five times. With the
  // updates each leg drifts ½·b·T² and the velocity restarts from zero.
  const double b = 0.02;
  Signal s;
  StillResult still;
  for (int k = 0; k < 2000; ++k) {
    const double t = k * kDt;
    s.t.push_back(t);
    s.f.emplace_back(b, 0.0, kG);
    still.still.push_back(std::fmod(t, 4.0) >= 2.0);
  }
  IntegrateOptions o;
  o.mount = MountMode::kZUp;
  const IntegrationResult with = IntegrateTrajectory(s.t, s.f, {}, still, o);
  o.zero_velocity_updates = false;
  const IntegrationResult without = IntegrateTrajectory(s.t, s.f, {}, still, o);
  EXPECT_NEAR(with.path.position_m.back().x(), 5 * 0.5 * b * 4.0, 0.01);
  EXPECT_NEAR(without.path.position_m.back().x(), 0.5 * b * 20.0 * 20.0, 0.01);
  EXPECT_GT(with.zero_velocity_samples, 900u);
}

TEST(AlignToReference, PlacesAndRotatesACopyOntoTheOriginal) {
  TimedPath ref;
  TimedPath path;
  const Eigen::Matrix3d rot =
      Eigen::AngleAxisd(1.1, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  for (int i = 0; i <= 100; ++i) {
    const double t = 0.1 * i;
    const Eigen::Vector3d p(3.0 * std::sin(0.3 * t) + t, 2.0 * t, 0.1 * t);
    ref.time_s.push_back(t);
    ref.position_m.push_back(p + Eigen::Vector3d(10, 20, 30));
    path.time_s.push_back(t);
    path.position_m.push_back(rot * p);
  }
  const double angle = AlignToReference(path, ref, 0.0, 3.0);
  EXPECT_NEAR(angle, -1.1, 1e-12);
  for (std::size_t i = 0; i < ref.size(); ++i) {
    EXPECT_NEAR((path.position_m[i] - ref.position_m[i]).norm(), 0.0, 1e-9);
  }
}

TEST(HorizontalPathLength, JitterAtRestDoesNotAddUp) {
  std::mt19937 rng(5);
  std::normal_distribution<double> n(0.0, 0.01);
  std::vector<Eigen::Vector3d> p;
  for (int i = 0; i < 500; ++i) p.emplace_back(n(rng), n(rng), 0.0);             // rest
  for (int i = 1; i <= 100; ++i) p.emplace_back(0.2 * i + n(rng), n(rng), 0.0);  // 20 m
  for (int i = 0; i < 500; ++i) p.emplace_back(20.0 + n(rng), n(rng), 0.0);      // rest
  // Every step counted would add ~1000 × 1.8 cm.
  EXPECT_NEAR(HorizontalPathLength(p, 0.25), 20.0, 0.3);
  EXPECT_GT(HorizontalPathLength(p, 0.0), 30.0);
}

TEST(ComparePaths, GivesTheHorizontalFiguresAtTheReferenceEpochs) {
  TimedPath ref, path;
  for (int i = 0; i <= 10; ++i) {
    ref.time_s.push_back(i);
    ref.position_m.emplace_back(i, 0.0, 0.0);
    // 0.5 m to the side and 7 m up: height does not count.
    path.time_s.push_back(i);
    path.position_m.emplace_back(i, i == 10 ? 2.0 : 0.5, 7.0);
  }
  const PathMetrics m = ComparePaths(path, ref, 0.0);
  EXPECT_NEAR(m.horizontal_max_m, 2.0, 1e-12);
  EXPECT_NEAR(m.horizontal_rms_m, std::sqrt((10 * 0.25 + 4.0) / 11.0), 1e-12);
  EXPECT_NEAR(m.start_end_distance_m, std::hypot(10.0, 1.5), 1e-12);
  EXPECT_NEAR(m.path_length_m, 9.0 + std::hypot(1.0, 1.5), 1e-12);
}

TEST(MountMode, NamesRoundTrip) {
  EXPECT_EQ(ParseMountMode(ToString(MountMode::kLevel)), MountMode::kLevel);
  EXPECT_EQ(ParseMountMode(ToString(MountMode::kZUp)), MountMode::kZUp);
  EXPECT_FALSE(ParseMountMode("sideways").has_value());
}

}  // namespace
}  // namespace mpcal
