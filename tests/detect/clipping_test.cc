// Clipped readings: samples at the sensor's range limit are not used, and a
// position that contains them is dropped with a warning naming its time.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "findings.h"
#include "mpcal/detect.h"
#include "mpcal/error.h"
#include "mpcal/units.h"

namespace mpcal {
namespace {

using test::Names;
using test::Words;
using ::testing::HasSubstr;

constexpr double kRateHz = 50.0;
constexpr double kDwellS = 4.0;
constexpr double kTurnS = 1.5;
constexpr double kNoiseMps2 = 0.01;

struct Session {
  Recording recording;
  std::vector<double> position_start_s;  // start of each still position
};

// Still positions along `down` (unit vectors: what gravity reads) with white
// noise, joined by turns with hand shake. Every reading is then passed
// through `sensor` (offset, range, quantisation).
template <typename Sensor>
Session Make(const std::vector<Eigen::Vector3d>& down, double shake_mps2, Sensor sensor) {
  Session s;
  std::mt19937_64 rng(5);
  std::normal_distribution<double> gauss(0.0, 1.0);
  auto emit = [&](const Eigen::Vector3d& f, double extra) {
    Eigen::Vector3d y = f;
    for (int k = 0; k < 3; ++k) y[k] += kNoiseMps2 * gauss(rng) + extra * gauss(rng);
    s.recording.time_s.push_back(static_cast<double>(s.recording.size()) / kRateHz);
    s.recording.accel.push_back(sensor(y));
  };
  Eigen::Vector3d previous = down.front();
  for (const Eigen::Vector3d& d : down) {
    const int turn = static_cast<int>(kTurnS * kRateHz);
    for (int i = 1; i <= turn; ++i) {
      const double u = static_cast<double>(i) / turn;
      emit(kStandardGravityMps2 * ((1 - u) * previous + u * d).normalized(), shake_mps2);
    }
    s.position_start_s.push_back(static_cast<double>(s.recording.size()) / kRateHz);
    for (int i = 0; i < static_cast<int>(kDwellS * kRateHz); ++i)
      emit(kStandardGravityMps2 * d, 0.0);
    previous = d;
  }
  s.recording.units = AccelUnits::kMps2;
  s.recording.source = "clipping";
  return s;
}

// The six faces and eight corners of the cube.
std::vector<Eigen::Vector3d> Directions() {
  std::vector<Eigen::Vector3d> d;
  for (int k = 0; k < 3; ++k) {
    d.push_back(Eigen::Vector3d::Unit(k));
    d.push_back(-Eigen::Vector3d::Unit(k));
  }
  for (int i = 0; i < 8; ++i) {
    d.push_back(Eigen::Vector3d((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1)
                    .normalized());
  }
  return d;
}

// The start time a warning "position 12.3-15.6 s dropped: ..." names.
double WarnedStartS(const std::string& warning) {
  const auto at = warning.find("position ");
  return at == std::string::npos ? -1.0 : std::stod(warning.substr(at + 9));
}

Eigen::Vector3d Clip(const Eigen::Vector3d& y, double limit) {
  return y.cwiseMax(-limit).cwiseMin(limit);
}

TEST(Clipping, RangeBelowOneGDropsThePositionsAtTheLimitAndNamesTheirTimes) {
  // A ±0.92 g sensor: every face position pins one axis at the limit, the
  // corners (0.58 g per axis) stay inside.
  const double limit = 9.0;
  const Session s =
      Make(Directions(), 1.0, [&](const Eigen::Vector3d& y) { return Clip(y, limit); });
  DetectOptions options;
  options.range_mps2 = limit;
  const DetectResult r = DetectStatic(s.recording, options);
  EXPECT_EQ(r.dropped_clipped, 6);
  EXPECT_EQ(r.intervals.size(), 8u);
  for (const StaticInterval& iv : r.intervals) {
    EXPECT_LT(iv.mean.cwiseAbs().maxCoeff(), 0.99 * limit);
  }
  ASSERT_EQ(Words(r.notes).size(), 6u);
  EXPECT_THAT(Words(r.notes)[0], HasSubstr("range limit"));
  // In time order: the six faces come first.
  for (int k = 0; k < 6; ++k) {
    EXPECT_GE(WarnedStartS(Words(r.notes)[k]), s.position_start_s[k] - 0.05)
        << Words(r.notes)[k];
    EXPECT_LT(WarnedStartS(Words(r.notes)[k]), s.position_start_s[k] + kDwellS)
        << Words(r.notes)[k];
  }
  EXPECT_GT(r.clipped_samples, 6u * static_cast<std::size_t>(kDwellS * kRateHz) / 2);
}

TEST(Clipping, WithoutTheRangeALimitBelowOneAndAHalfGIsNotGuessed) {
  // Documented: the limit found from the data must be 1.5 g from zero, so a
  // quantised still reading at 1 g is never taken for one; a sensor with a
  // smaller range needs range_mps2.
  const Session s =
      Make(Directions(), 1.0, [](const Eigen::Vector3d& y) { return Clip(y, 9.0); });
  const DetectResult r = DetectStatic(s.recording, DetectOptions{});
  EXPECT_EQ(r.clipped_samples, 0u);
  EXPECT_EQ(r.dropped_clipped, 0);
  EXPECT_EQ(r.intervals.size(), Directions().size());
}

TEST(Clipping, ALimitFoundFromTheDataDropsAPositionPinnedAtIt) {
  // A ±2 g sensor with a 1.2 g offset on z: with +z up it reads 2.2 g and
  // sticks at the limit; the hand shake of the turns hits it too.
  const double limit = 2.0 * kStandardGravityMps2;
  const Session s = Make(Directions(), 6.0, [&](const Eigen::Vector3d& y) {
    return Clip(y + Eigen::Vector3d(0, 0, 1.2 * kStandardGravityMps2), limit);
  });
  const DetectResult r = DetectStatic(s.recording, DetectOptions{});
  EXPECT_GT(r.clipped_samples, static_cast<std::size_t>(kDwellS * kRateHz) / 2);
  // +z (index 4) and the four corners with +z all read more than 1.58 g; only
  // the face is pinned.
  EXPECT_EQ(r.dropped_clipped, 1);
  ASSERT_EQ(Words(r.notes).size(), 1u);
  EXPECT_THAT(Words(r.notes)[0], HasSubstr("z >= 19.6133"));
  EXPECT_GE(WarnedStartS(Words(r.notes)[0]), s.position_start_s[4] - 0.05)
      << Words(r.notes)[0];
  EXPECT_LT(WarnedStartS(Words(r.notes)[0]), s.position_start_s[4] + kDwellS)
      << Words(r.notes)[0];
  for (const StaticInterval& iv : r.intervals) EXPECT_LT(iv.mean.z(), 0.99 * limit);
}

TEST(Clipping, QuantisedStillReadingsAtOneGAreNotClipping) {
  // Readings printed with few decimals repeat exactly while still, the
  // largest of them too.
  const Session s = Make(Directions(), 1.0, [](const Eigen::Vector3d& y) {
    return Eigen::Vector3d((y / 0.04).array().round() * 0.04);
  });
  const DetectResult r = DetectStatic(s.recording, DetectOptions{});
  EXPECT_EQ(r.clipped_samples, 0u);
  EXPECT_TRUE(Words(r.notes).empty());
  EXPECT_EQ(r.intervals.size(), Directions().size());
}

TEST(Clipping, AllPositionsClippedGivesAMessageThatSaysSo) {
  const Session s = Make({Eigen::Vector3d::UnitZ(), -Eigen::Vector3d::UnitZ()},
                         1.0,
                         [](const Eigen::Vector3d& y) { return Clip(y, 9.0); });
  DetectOptions options;
  options.range_mps2 = 9.0;
  const DetectResult r = DetectStatic(s.recording, options);
  EXPECT_TRUE(r.intervals.empty());
  EXPECT_EQ(r.dropped_clipped, 2);
  EXPECT_EQ(r.finding.kind, DetectOutcome::kAllClipped);
  EXPECT_THAT(Describe(r.finding), HasSubstr("range limit"));
  EXPECT_TRUE(Names(r.finding.advice, Option::kSensorRange));
}

TEST(Clipping, NegativeOrNonFiniteRangeIsRejected) {
  DetectOptions options;
  options.range_mps2 = -1.0;
  EXPECT_THAT(options.Validate(), HasSubstr("range_mps2"));
  options.range_mps2 = std::nan("");
  EXPECT_THAT(options.Validate(), HasSubstr("range_mps2"));
  Recording r;
  r.time_s = {0.0, 0.1, 0.2};
  r.accel.assign(3, Eigen::Vector3d(0, 0, kStandardGravityMps2));
  EXPECT_THROW(DetectStatic(r, options), Error);
}

}  // namespace
}  // namespace mpcal
