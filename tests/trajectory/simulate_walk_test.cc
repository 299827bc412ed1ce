// The synthetic walk: closed loop, consistent readings, reference and truth.
#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mpcal/error.h"
#include "mpcal/gnss.h"
#include "mpcal/simulate_walk.h"

namespace mpcal {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

SimulateWalkOptions Options(bool turn) {
  SimulateWalkOptions o;
  o.device = FindPreset("mti-g");
  o.turn = turn;
  o.seed = 3;
  return o;
}

TEST(SimulateWalk, DefaultOptionsAreValid) {
  EXPECT_EQ(Options(false).Validate(), "");
  SimulateWalkOptions o = Options(false);
  o.length_m = 1.0;
  EXPECT_THAT(o.Validate(), HasSubstr("too short"));
  EXPECT_THAT([&] { SimulateWalk(o); }, ThrowsMessage<Error>(HasSubstr("simulate walk")));
  EXPECT_THROW(SimulateWalk(Options(false), 3.0), Error);
}

TEST(SimulateWalk, TheLoopClosesAndHasTheExpectedLength) {
  const SimulatedWalk w = SimulateWalk(Options(false));
  EXPECT_NEAR((w.true_enu_m.back() - w.true_enu_m.front()).norm(), 0.0, 1e-9);
  // 2 × (40 + 25) m, corners jittered by up to 1 m, plus the sideways sway.
  EXPECT_NEAR(w.true_path_length_m, 130.0, 5.0);
  EXPECT_TRUE(w.recording.gyro_radps.empty());
  // 512 Hz over the walk; rests of 20 s at both ends.
  const double duration = w.recording.time_s.back() - w.recording.time_s.front();
  EXPECT_NEAR(static_cast<double>(w.recording.size()), duration * 512.0 + 1.0, 1.0);
  EXPECT_GT(duration, 130.0 / 1.2 + 40.0);
}

TEST(SimulateWalk, ReadingsAtRestAreTheDevicesForwardModelOfGravity) {
  const SimulateWalkOptions o = Options(false);
  const SimulatedWalk w = SimulateWalk(o, 9.78);
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  const int n = 5000;  // ~10 s of the initial rest
  for (int i = 0; i < n; ++i) mean += w.recording.accel[i];
  mean /= n;
  // Corrected with the truth, the rest reads gravity's magnitude, up to the
  // noise of the mean: σ = 0.002·√256 / √5000 per axis.
  constexpr double kMeanTol = 5 * 0.032 / 70.7;
  EXPECT_NEAR(w.truth.Correct(mean).norm(), 9.78, kMeanTol);
  EXPECT_GT((mean - w.truth.Correct(mean)).norm(), 0.1);  // the errors are there
  EXPECT_DOUBLE_EQ(w.truth.gravity_mps2, 9.78);
}

TEST(SimulateWalk, TurningWalkHasGyroscopeTurningAFullCircle) {
  const SimulatedWalk w = SimulateWalk(Options(true));
  ASSERT_EQ(w.recording.gyro_radps.size(), w.recording.size());
  // Three turns of about 90° each (the corners are jittered): the integral of
  // the rate about the vertical, less the bias seen at rest, is near 3π/2.
  double bias = 0.0;
  const int rest = 5000;  // ~10 s of the initial rest at 512 Hz
  for (int i = 0; i < rest; ++i) bias += w.recording.gyro_radps[i].z() / rest;
  double yaw = 0.0;
  for (std::size_t i = 1; i < w.recording.size(); ++i) {
    yaw += (w.recording.gyro_radps[i].z() - bias) *
           (w.recording.time_s[i] - w.recording.time_s[i - 1]);
  }
  EXPECT_NEAR(std::abs(yaw), 1.5 * M_PI, 0.2);
}

TEST(SimulateWalk, ReferenceIsAtFiveHertzWithCentimetreNoise) {
  const SimulateWalkOptions o = Options(false);
  const SimulatedWalk w = SimulateWalk(o);
  const GnssTrack ref = ParseGnss(FormatRtklibPos(w.gnss), "walk.pos");
  ASSERT_GT(ref.size(), 100u);
  EXPECT_NEAR(ref.time_s[1] - ref.time_s[0], 0.2, 1e-6);
  EXPECT_EQ(ref.time_system, TimeSystem::kGpst);
  EXPECT_NEAR(ref.origin->latitude_deg, o.origin.latitude_deg, 1e-6);
  // The first epoch is 0.2 s into the rest: the noise alone, 1 cm per axis.
  double sum_sq = 0.0;
  int count = 0;
  for (std::size_t i = 0; i < ref.size() && ref.time_s[i] < o.start_time_s + 15.0; ++i) {
    const Eigen::Vector3d d = ref.enu_m[i] - ref.enu_m[0];
    sum_sq += d.x() * d.x() + d.y() * d.y();
    ++count;
  }
  // Differences of two noisy epochs: σ√2 per axis, two axes.
  EXPECT_NEAR(std::sqrt(sum_sq / count), 0.01 * 2.0, 0.006);
}

TEST(SimulateWalk, SameSeedSameWalk) {
  const SimulatedWalk a = SimulateWalk(Options(true));
  const SimulatedWalk b = SimulateWalk(Options(true));
  ASSERT_EQ(a.recording.size(), b.recording.size());
  EXPECT_EQ(a.recording.accel[12345], b.recording.accel[12345]);
  SimulateWalkOptions o = Options(true);
  o.seed = 4;
  EXPECT_NE(SimulateWalk(o).recording.accel[12345], a.recording.accel[12345]);
}

}  // namespace
}  // namespace mpcal
