// Where the turns start and stop (detect.h, ExtendToMotion), on recordings made
// here sample by sample: rests joined by minimum-jerk turns, as a hand turns.
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "mpcal/detect.h"
#include "mpcal/recording.h"

namespace mpcal {
namespace {

constexpr double kTurnRateHz = 100.0;
constexpr double kGravity = 9.81;

// Rest [0, 10) s, a 90° turn about x over [10, 12), rest [12, 22) s, a 90°
// turn about y over [22, 24), rest to 34 s. Noise σ per sample (0: none).
struct TurnSession {
  Recording recording;
  std::vector<StaticInterval> detected;  // trimmed by 0.8 s at each end
  std::vector<double> turn_start_s = {10.0, 22.0};
  std::vector<double> turn_end_s = {12.0, 24.0};
};

StaticInterval Interval(const Recording& r, double from_s, double to_s) {
  StaticInterval in;
  in.begin = static_cast<std::size_t>(std::lround(from_s * kTurnRateHz));
  in.end = static_cast<std::size_t>(std::lround(to_s * kTurnRateHz));
  in.start_s = r.time_s[in.begin];
  in.end_s = r.time_s[in.end - 1];
  const auto n = static_cast<double>(in.end - in.begin);
  for (std::size_t i = in.begin; i < in.end; ++i) in.mean += r.accel[i] / n;
  for (std::size_t i = in.begin; i < in.end; ++i) {
    in.std += (r.accel[i] - in.mean).cwiseAbs2() / (n - 1.0);
  }
  in.std = in.std.cwiseSqrt();
  return in;
}

TurnSession MakeSession(unsigned seed, double gyro_sigma, double accel_sigma) {
  TurnSession s;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal;
  const Eigen::Vector3d bias(0.01, -0.02, 0.005);
  const std::size_t n = 34 * static_cast<std::size_t>(kTurnRateHz);
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();  // body to level
  const Eigen::Vector3d axes[2] = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY()};
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / kTurnRateHz;
    Eigen::Vector3d rate = Eigen::Vector3d::Zero();
    for (int k = 0; k < 2; ++k) {
      const double tau = (t - s.turn_start_s[k]) / 2.0;
      if (tau > 0.0 && tau < 1.0) {
        // Minimum jerk: angle (π/2)(10τ³ − 15τ⁴ + 6τ⁵), rate 30 τ²(1 − τ)² (π/2)/T.
        rate = axes[k] * (std::numbers::pi / 2.0) * 30.0 * tau * tau * (1 - tau) *
               (1 - tau) / 2.0;
      }
    }
    q = q * Eigen::Quaterniond(Eigen::AngleAxisd(
                rate.norm() / kTurnRateHz,
                rate.norm() > 0 ? rate.normalized() : Eigen::Vector3d::UnitZ()));
    Eigen::Vector3d noise_g(normal(rng), normal(rng), normal(rng));
    Eigen::Vector3d noise_a(normal(rng), normal(rng), normal(rng));
    s.recording.time_s.push_back(t);
    s.recording.gyro_radps.push_back(rate + bias + gyro_sigma * noise_g);
    s.recording.accel.push_back(q.conjugate() * Eigen::Vector3d(0, 0, kGravity) +
                                accel_sigma * noise_a);
  }
  s.detected = {Interval(s.recording, 0.8, 9.2),
                Interval(s.recording, 12.8, 21.2),
                Interval(s.recording, 24.8, 33.2)};
  return s;
}

TEST(ExtendToMotion, ReachesTheMotionAndNotBeyond) {
  int edges = 0;
  int near = 0;  // within 0.2 s of the motion: the two windows of 50 ms put
                 // back, and the minimum jerk's slow start under the noise
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const TurnSession s = MakeSession(seed, 0.005, 0.02);
    const std::vector<StaticInterval> e = ExtendToMotion(s.recording, s.detected);
    ASSERT_EQ(e.size(), 3u);
    for (std::size_t k = 0; k < 2; ++k) {
      const double end_s = s.recording.time_s[e[k].end - 1];
      const double begin_s = s.recording.time_s[e[k + 1].begin];
      // Never into the turn, and never shorter than detected.
      EXPECT_LE(end_s, s.turn_start_s[k]) << "seed " << seed << " turn " << k;
      EXPECT_GE(begin_s, s.turn_end_s[k]) << "seed " << seed << " turn " << k;
      EXPECT_GE(e[k].end, s.detected[k].end);
      EXPECT_LE(e[k + 1].begin, s.detected[k + 1].begin);
      near += (end_s >= s.turn_start_s[k] - 0.2) + (begin_s <= s.turn_end_s[k] + 0.2);
      edges += 2;
      EXPECT_EQ(e[k].end_s, end_s);
      EXPECT_EQ(e[k + 1].start_s, begin_s);
    }
    // The means and scatters stay the detected ones.
    EXPECT_EQ(e[1].mean, s.detected[1].mean);
    EXPECT_EQ(e[1].std, s.detected[1].std);
  }
  // A window of the rest's noise stops a position short once in 10⁴: over
  // the 60 windows of 0.6 s, about 1 edge in 170.
  EXPECT_GE(near, edges - 2);
}

TEST(ExtendToMotion, AQuantisedSensorThatNeverMovesAtRestGrowsToo) {
  const TurnSession s = MakeSession(1, 0.0, 0.0);  // readings constant at rest
  const std::vector<StaticInterval> e = ExtendToMotion(s.recording, s.detected);
  const double end_s = s.recording.time_s[e[0].end - 1];
  EXPECT_LE(end_s, s.turn_start_s[0]);
  EXPECT_GE(end_s, s.turn_start_s[0] - 0.2);
}

TEST(ExtendToMotion, APositionNeverReachesPastItsNeighbour) {
  // Two detected pieces of one rest, 1 s apart: they meet, and do not cross.
  const TurnSession s = MakeSession(3, 0.005, 0.02);
  const std::vector<StaticInterval> pieces = {Interval(s.recording, 1.0, 4.0),
                                              Interval(s.recording, 5.0, 9.0)};
  const std::vector<StaticInterval> e = ExtendToMotion(s.recording, pieces);
  EXPECT_LE(e[0].end, pieces[1].begin);
  EXPECT_GE(e[1].begin, e[0].end);
  EXPECT_GT(e[0].end, pieces[0].end);
}

}  // namespace
}  // namespace mpcal
