// StillnessMonitor: whether a record is still throughout, decided as its
// rows arrive, by DetectStatic's rule and with DetectStatic's figures.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <random>
#include <span>
#include <vector>

#include <gtest/gtest.h>

#include "detect/motion_statistic.h"
#include "mpcal/detect.h"
#include "mpcal/error.h"
#include "mpcal/units.h"

namespace mpcal {
namespace {

// A record as a log reader hands it over.
struct Rows {
  std::vector<double> t;
  std::vector<Eigen::Vector3d> a;

  Recording AsRecording() const {
    Recording r;
    r.time_s = t;
    r.accel = a;
    r.units = AccelUnits::kMps2;
    r.source = "<simulated>";
    return r;
  }
};

// A sensor at rest with gravity along +z and white noise of `sigma_mps2` per
// axis; with turn_s > 0, turned by 90 deg about y (gravity from +z to +x,
// a smooth start and stop) over turn_s from turn_at_s, still on either side.
struct StillMaker {
  double rate_hz = 200.0;
  double duration_s = 600.0;
  double sigma_mps2 = 0.02;
  double turn_at_s = 0.0;
  double turn_s = 0.0;
  std::uint64_t seed = 11;

  Rows Make() const {
    Rows r;
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> gauss(0.0, sigma_mps2);
    const auto n = static_cast<std::size_t>(duration_s * rate_hz);
    for (std::size_t i = 0; i < n; ++i) {
      const double t = static_cast<double>(i) / rate_hz;
      const double s =
          turn_s > 0.0 ? std::clamp((t - turn_at_s) / turn_s, 0.0, 1.0) : 0.0;
      const double angle = 0.5 * std::numbers::pi * s * s * (3.0 - 2.0 * s);
      const Eigen::Vector3d f(kStandardGravityMps2 * std::sin(angle),
                              0.0,
                              kStandardGravityMps2 * std::cos(angle));
      r.t.push_back(t);
      r.a.push_back(f + Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)));
    }
    return r;
  }
};

// The verdict with the rows fed in pieces of the given sizes (the last one
// takes what is left; none: one piece).
StillVerdict Feed(const Rows& r,
                  const std::vector<std::size_t>& sizes = {},
                  const DetectOptions& options = {}) {
  StillnessMonitor monitor(options, AccelUnits::kMps2);
  const std::span<const double> t(r.t);
  const std::span<const Eigen::Vector3d> a(r.a);
  std::size_t at = 0;
  for (const std::size_t size : sizes) {
    const std::size_t m = std::min(size, t.size() - at);
    monitor.Add(t.subspan(at, m), a.subspan(at, m));
    at += m;
  }
  monitor.Add(t.subspan(at), a.subspan(at));
  return monitor.Verdict();
}

std::vector<std::size_t> OneRowPieces(const Rows& r) {
  return std::vector<std::size_t>(r.t.size(), 1);
}

std::vector<std::size_t> RandomPieces(const Rows& r, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  // Mostly short pieces (shorter than a window, a resync, the period's
  // 4096 rows), some long.
  std::uniform_int_distribution<std::size_t> small(0, 300);
  std::uniform_int_distribution<std::size_t> large(0, 40000);
  std::vector<std::size_t> sizes;
  for (std::size_t at = 0; at < r.t.size();) {
    sizes.push_back(rng() % 4 == 0 ? large(rng) : small(rng));
    at += sizes.back();
  }
  return sizes;
}

void ExpectSameVerdict(const StillVerdict& x, const StillVerdict& y) {
  // The same sums in the same order: the same figures bit for bit.
  EXPECT_EQ(x.reason, y.reason);
  EXPECT_EQ(x.still, y.still);
  EXPECT_EQ(x.quiet_level, y.quiet_level);
  EXPECT_EQ(x.threshold, y.threshold);
  EXPECT_EQ(x.largest_statistic, y.largest_statistic);
  EXPECT_EQ(x.largest_at_s, y.largest_at_s);
  EXPECT_EQ(x.gap_at_s, y.gap_at_s);
  EXPECT_EQ(x.windows, y.windows);
  EXPECT_EQ(x.window_samples, y.window_samples);
  EXPECT_EQ(x.sample_period_s, y.sample_period_s);
}

// 15 minutes at 200 Hz: 179,800 windows, more than the 2^17 kept, so every
// other window makes the quiet level.
Rows StillRecord() { return StillMaker{.duration_s = 900.0}.Make(); }
// 10 minutes with a 2-second turn at 300 s.
Rows MovingRecord() { return StillMaker{.turn_at_s = 300.0, .turn_s = 2.0}.Make(); }

TEST(StillnessMonitor, AStillRecordIsStill) {
  const Rows r = StillRecord();
  const StillVerdict v = Feed(r);
  EXPECT_TRUE(v.still);
  EXPECT_EQ(v.reason, NotStillReason::kNone);
  EXPECT_EQ(v.window_samples, 201u);
  EXPECT_NEAR(v.sample_period_s, 0.005, 1e-12);
  EXPECT_EQ(v.windows, r.t.size() - 200);
  EXPECT_DOUBLE_EQ(v.threshold, 3.0 * v.quiet_level);
  EXPECT_LE(v.largest_statistic, v.threshold);
  // The statistic of a still window is sqrt(3) sigma, give or take
  // sqrt(3 / (2 x 200)) of it: the 5 % quantile lies a little below.
  EXPECT_GT(v.quiet_level, 0.85 * std::sqrt(3.0) * 0.02);
  EXPECT_LT(v.quiet_level, std::sqrt(3.0) * 0.02);
}

TEST(StillnessMonitor, TheQuietLevelIsTheQuantileOfEveryOtherWindowPastTwoToThe17) {
  const Rows r = StillRecord();
  const StillVerdict v = Feed(r, RandomPieces(r, 3));
  const std::size_t half = 100;
  std::vector<double> every_other;
  internal::ForEachWindow(r.a, half, [&](std::size_t c, double s) {
    if ((c - half) % 2 == 0) every_other.push_back(s);
  });
  ASSERT_GT(2 * every_other.size(), std::size_t{1} << 17);
  EXPECT_EQ(v.quiet_level, internal::Quantile(every_other, 0.05));
}

TEST(StillnessMonitor, AgreesWithDetectStaticOnAStillRecord) {
  const Rows r = StillRecord();
  const StillVerdict v = Feed(r);
  const DetectResult d = DetectStatic(r.AsRecording(), {});
  ASSERT_EQ(d.intervals.size(), 1u);
  EXPECT_EQ(v.window_samples, d.window_samples);
  EXPECT_DOUBLE_EQ(v.sample_period_s, d.sample_period_s);
  // A sample of every other window against the exact quantile: the
  // neighbouring windows share all but two samples, so within a percent.
  EXPECT_NEAR(v.quiet_level / d.quiet_level, 1.0, 0.01);
  EXPECT_NEAR(v.threshold / d.threshold, 1.0, 0.01);
}

TEST(StillnessMonitor, ATurnInTheMiddleIsMovedWhereItTurned) {
  const Rows r = MovingRecord();
  const StillVerdict v = Feed(r);
  EXPECT_FALSE(v.still);
  EXPECT_EQ(v.reason, NotStillReason::kMoved);
  EXPECT_GT(v.largest_statistic, 10.0 * v.threshold);
  EXPECT_GE(v.largest_at_s, 300.0);
  EXPECT_LE(v.largest_at_s, 302.0);
  // Detection finds the positions on either side, at the same quiet level.
  const DetectResult d = DetectStatic(r.AsRecording(), {});
  EXPECT_GE(d.intervals.size(), 2u);
  EXPECT_NEAR(v.quiet_level / d.quiet_level, 1.0, 0.01);
  EXPECT_NEAR(v.threshold / d.threshold, 1.0, 0.01);
}

TEST(StillnessMonitor, TheVerdictDoesNotDependOnHowTheRowsAreSplit) {
  for (const Rows& r : {StillRecord(), MovingRecord()}) {
    const StillVerdict whole = Feed(r);
    ExpectSameVerdict(whole, Feed(r, OneRowPieces(r)));
    ExpectSameVerdict(whole, Feed(r, RandomPieces(r, 1)));
    ExpectSameVerdict(whole, Feed(r, RandomPieces(r, 2)));
  }
}

TEST(StillnessMonitor, TheWindowIsSizedFromTheFirst4096Rows) {
  // 200 Hz for the first 4096 rows, then slower and jittered (5-7 ms): the
  // whole record's typical period is longer, the first rows' is 5 ms.
  Rows r = StillMaker{.duration_s = 120.0}.Make();
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> dt(0.005, 0.007);
  for (std::size_t i = 4096; i < r.t.size(); ++i) r.t[i] = r.t[i - 1] + dt(rng);
  const StillVerdict whole = Feed(r);
  EXPECT_NEAR(whole.sample_period_s, 0.005, 1e-12);
  EXPECT_EQ(whole.window_samples, 201u);
  ExpectSameVerdict(whole, Feed(r, OneRowPieces(r)));
  ExpectSameVerdict(whole, Feed(r, RandomPieces(r, 4)));
}

TEST(StillnessMonitor, AReadingBeyondOneAndAHalfGIsAtTheRangeLimit) {
  Rows r = StillMaker{.duration_s = 60.0}.Make();
  r.a[4000].z() = 1.6 * kStandardGravityMps2;
  const StillVerdict v = Feed(r);
  EXPECT_EQ(v.reason, NotStillReason::kRangeLimit);
  EXPECT_EQ(v.gap_at_s, r.t[4000]);
  // A sensor of +-2 g reads 1.6 g: not its limit, but a bump all the same.
  DetectOptions two_g;
  two_g.range_mps2 = 2.0 * kStandardGravityMps2;
  EXPECT_EQ(Feed(r, {}, two_g).reason, NotStillReason::kMoved);
  // ... and 99 % of its range is.
  r.a[4000].z() = 0.995 * 2.0 * kStandardGravityMps2;
  EXPECT_EQ(Feed(r, {}, two_g).reason, NotStillReason::kRangeLimit);
  // Negative readings too, on any axis.
  r.a[4000] = Eigen::Vector3d(-1.6 * kStandardGravityMps2, 0.0, kStandardGravityMps2);
  EXPECT_EQ(Feed(r).reason, NotStillReason::kRangeLimit);
}

TEST(StillnessMonitor, AHoleInTimeLongerThanTheWindowIsAGap) {
  Rows r = StillMaker{.duration_s = 60.0}.Make();
  for (std::size_t i = 6000; i < r.t.size(); ++i) r.t[i] += 3.0;
  const StillVerdict v = Feed(r, RandomPieces(r, 5));
  EXPECT_EQ(v.reason, NotStillReason::kGap);
  EXPECT_EQ(v.gap_at_s, r.t[5999]);
  // Still otherwise: a gap shorter than the window is not one.
  for (std::size_t i = 6000; i < r.t.size(); ++i) r.t[i] -= 2.5;
  EXPECT_TRUE(Feed(r).still);
}

TEST(StillnessMonitor, FewerRowsThanOneWindowGiveNoVerdict) {
  // 100 Hz and a 1 s window: 101 samples.
  Rows r = StillMaker{.rate_hz = 100.0, .duration_s = 1.0}.Make();
  ASSERT_EQ(r.t.size(), 100u);
  const StillVerdict v = Feed(r);
  EXPECT_FALSE(v.still);
  EXPECT_EQ(v.reason, NotStillReason::kTooShort);
  EXPECT_EQ(v.window_samples, 101u);
  EXPECT_EQ(v.windows, 0u);
  // One more row is one window.
  r.t.push_back(1.0);
  r.a.push_back(r.a.back());
  const StillVerdict one = Feed(r, OneRowPieces(r));
  EXPECT_EQ(one.windows, 1u);
  EXPECT_TRUE(one.still);
  // Nothing at all.
  EXPECT_EQ(StillnessMonitor({}, AccelUnits::kG).Verdict().reason,
            NotStillReason::kTooShort);
}

TEST(StillnessMonitor, AValueNotFiniteEndsTheRecord) {
  Rows r = StillMaker{.duration_s = 60.0}.Make();
  r.a[5000].y() = std::numeric_limits<double>::quiet_NaN();
  StillVerdict v = Feed(r, RandomPieces(r, 7));
  EXPECT_EQ(v.reason, NotStillReason::kNotFinite);
  EXPECT_EQ(v.gap_at_s, r.t[4999]);
  // The first reason in time is the one given.
  for (std::size_t i = 3000; i < r.t.size(); ++i) r.t[i] += 2.0;
  v = Feed(r);
  EXPECT_EQ(v.reason, NotStillReason::kGap);
  EXPECT_EQ(v.gap_at_s, r.t[2999]);
  r.t[10] = std::numeric_limits<double>::infinity();
  EXPECT_EQ(Feed(r).reason, NotStillReason::kNotFinite);
}

TEST(StillnessMonitor, AQuantisedRecordIsStillByTheReadingStep) {
  // Readings printed to 0.01 m/s^2, the noise below that: most windows
  // never change (statistic 0, the quiet level 0), some flicker one step.
  Rows r = StillMaker{.duration_s = 300.0, .sigma_mps2 = 0.0015}.Make();
  for (auto& a : r.a) {
    a.z() += 9.80 - kStandardGravityMps2;  // on a step, so the flicker is rare
    a = (a.array() * 100.0).round() / 100.0;
  }
  const StillVerdict v = Feed(r);
  EXPECT_TRUE(v.still);
  EXPECT_NEAR(v.quiet_level, 0.005, 1e-9);  // half the step
  EXPECT_GT(v.largest_statistic, 0.0);      // it did flicker
  const DetectResult d = DetectStatic(r.AsRecording(), {});
  ASSERT_EQ(d.intervals.size(), 1u);
  EXPECT_NEAR(v.threshold, d.threshold, 1e-9);
}

TEST(StillnessMonitor, RawCountsGiveNoVerdict) {
  const Rows r = StillMaker{.duration_s = 30.0}.Make();
  StillnessMonitor monitor({}, AccelUnits::kCounts);
  monitor.Add(r.t, r.a);
  const StillVerdict v = monitor.Verdict();
  EXPECT_FALSE(v.still);
  EXPECT_EQ(v.reason, NotStillReason::kTooShort);
  EXPECT_EQ(v.windows, 0u);
}

TEST(StillnessMonitor, ReadingsInGGiveTheFiguresInG) {
  const Rows mps2 = StillMaker{.duration_s = 30.0}.Make();
  Rows g = mps2;
  for (auto& a : g.a) a /= kStandardGravityMps2;
  StillnessMonitor monitor({}, AccelUnits::kG);
  monitor.Add(g.t, g.a);
  const StillVerdict v = monitor.Verdict();
  const StillVerdict in_mps2 = Feed(mps2);
  EXPECT_TRUE(v.still);
  EXPECT_NEAR(v.quiet_level * kStandardGravityMps2 / in_mps2.quiet_level, 1.0, 1e-9);
  EXPECT_NEAR(v.threshold * kStandardGravityMps2 / in_mps2.threshold, 1.0, 1e-9);
}

TEST(StillnessMonitor, RejectsWhatDetectStaticRejects) {
  DetectOptions bad;
  bad.quiet_quantile = 1.5;
  EXPECT_THROW(StillnessMonitor(bad, AccelUnits::kMps2), Error);

  const Rows r = StillMaker{.duration_s = 30.0}.Make();
  StillnessMonitor monitor({}, AccelUnits::kMps2);
  monitor.Add(std::span(r.t).first(10), std::span(r.a).first(10));
  const std::vector<double> back{r.t[5]};
  const std::vector<Eigen::Vector3d> reading{r.a[5]};
  try {
    monitor.Add(back, reading);
    ADD_FAILURE() << "time going back was taken";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kTime);
  }
  EXPECT_THROW(monitor.Add(back, {}), Error);

  DetectOptions short_window;
  short_window.window_s = 0.006;  // less than two samples at 200 Hz
  StillnessMonitor too_short(short_window, AccelUnits::kMps2);
  try {
    too_short.Add(r.t, r.a);
    ADD_FAILURE() << "a window of one sample was taken";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kOption);
  }
}

}  // namespace
}  // namespace mpcal
