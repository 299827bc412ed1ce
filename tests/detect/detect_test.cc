#include "mpcal/detect.h"

#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>
#include <random>
#include <utility>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "findings.h"
#include "mpcal/error.h"
#include "mpcal/log_reader.h"
#include "mpcal/not_finite.h"
#include "mpcal/simulate.h"
#include "mpcal/units.h"
#include "test_util.h"

namespace mpcal {
namespace {

using test::Names;
using test::Words;
using ::testing::HasSubstr;
using testing::RealDataPath;

// A mean of n white-noise samples is within this many σ/√n of the truth.
constexpr double kMeanTolSigmas = 5.0;

// A hand-made session: still positions with white noise joined by turns (a
// smooth rotation between the directions plus hand shake), in any units.
struct Made {
  Recording recording;
  std::vector<std::pair<std::size_t, std::size_t>> still;  // [begin, end)
  std::vector<Eigen::Vector3d> truth;                      // mean reading per position
};

struct Maker {
  double rate_hz = 100.0;
  double noise = 0.02;  // per-axis σ, m/s²
  double turn_s = 2.0;
  double shake_mps2 = 1.0;  // RMS of the shake during a turn
  double scale = 1.0;       // units per m/s²
  double offset = 0.0;      // units
  bool round = false;       // quantise to whole units (ADC counts)
  std::uint64_t seed = 7;

  Made Make(const std::vector<std::pair<Eigen::Vector3d, double>>& positions) const {
    Made m;
    std::mt19937_64 rng(seed);
    std::normal_distribution<double> gauss(0.0, 1.0);
    auto emit = [&](const Eigen::Vector3d& f_mps2, double extra_sigma) {
      Eigen::Vector3d y = f_mps2;
      for (int k = 0; k < 3; ++k) y[k] += noise * gauss(rng) + extra_sigma * gauss(rng);
      y = Eigen::Vector3d::Constant(offset) + scale * y;
      if (round) y = y.array().round();
      m.recording.time_s.push_back(static_cast<double>(m.recording.size()) / rate_hz);
      m.recording.accel.push_back(y);
    };
    Eigen::Vector3d prev = positions.front().first.normalized();
    for (std::size_t p = 0; p < positions.size(); ++p) {
      const Eigen::Vector3d dir = positions[p].first.normalized();
      if (p > 0) {
        const auto turn_n = static_cast<std::size_t>(turn_s * rate_hz);
        for (std::size_t i = 0; i < turn_n; ++i) {
          const double s = (i + 0.5) / static_cast<double>(turn_n);
          const double smooth = s * s * (3 - 2 * s);
          Eigen::Vector3d d = ((1 - smooth) * prev + smooth * dir);
          if (d.norm() < 1e-6) d = Eigen::Vector3d::UnitX();  // opposite faces
          emit(kStandardGravityMps2 * d.normalized(),
               shake_mps2 * std::sin(std::numbers::pi * s));
        }
      }
      const std::size_t begin = m.recording.size();
      const auto dwell_n = static_cast<std::size_t>(positions[p].second * rate_hz);
      for (std::size_t i = 0; i < dwell_n; ++i) emit(kStandardGravityMps2 * dir, 0.0);
      m.still.emplace_back(begin, m.recording.size());
      m.truth.push_back(Eigen::Vector3d::Constant(offset) +
                        scale * kStandardGravityMps2 * dir);
      prev = dir;
    }
    m.recording.source = "<made>";
    return m;
  }
};

std::vector<std::pair<Eigen::Vector3d, double>> CubeFaces(double dwell_s) {
  std::vector<std::pair<Eigen::Vector3d, double>> out;
  for (int i = 0; i < 3; ++i) {
    out.emplace_back(Eigen::Vector3d::Unit(i), dwell_s);
    out.emplace_back(-Eigen::Vector3d::Unit(i), dwell_s);
  }
  return out;
}

// Every true still range holds exactly one interval, inside it, and no
// interval reaches into a turn.
void ExpectIntervalsMatch(const DetectResult& r,
                          const std::vector<std::pair<std::size_t, std::size_t>>& still) {
  ASSERT_EQ(r.intervals.size(), still.size());
  for (std::size_t k = 0; k < still.size(); ++k) {
    const StaticInterval& iv = r.intervals[k];
    EXPECT_GE(iv.begin, still[k].first) << "interval " << k;
    EXPECT_LE(iv.end, still[k].second) << "interval " << k;
    // Only the window's half and the settling may be lost at each end.
    EXPECT_GT(iv.samples(), (still[k].second - still[k].first) / 2) << "interval " << k;
  }
}

TEST(DetectOptions, DefaultsAreValid) { EXPECT_EQ(DetectOptions{}.Validate(), ""); }

TEST(DetectOptions, ValidateNamesTheBadField) {
  DetectOptions o;
  o.window_s = 0;
  EXPECT_THAT(o.Validate(), HasSubstr("window_s"));
  o = {};
  o.threshold_factor = 0.5;
  EXPECT_THAT(o.Validate(), HasSubstr("threshold_factor"));
  o = {};
  o.quiet_quantile = 1.0;
  EXPECT_THAT(o.Validate(), HasSubstr("quiet_quantile"));
  o = {};
  o.settle_s = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT(o.Validate(), HasSubstr("settle_s"));
  Made m = Maker{}.Make(CubeFaces(5));
  o = {};
  o.min_static_s = -1;
  EXPECT_THROW(DetectStatic(m.recording, o), Error);
}

TEST(DetectStatic, FindsEveryPositionOfAMadeSession) {
  const Made m = Maker{}.Make(CubeFaces(6.0));
  const DetectResult r = DetectStatic(m.recording, {});
  ExpectIntervalsMatch(r, m.still);
  for (std::size_t k = 0; k < r.intervals.size(); ++k) {
    const StaticInterval& iv = r.intervals[k];
    const double tol =
        kMeanTolSigmas * 0.02 / std::sqrt(static_cast<double>(iv.samples()));
    EXPECT_LT((iv.mean - m.truth[k]).cwiseAbs().maxCoeff(), tol) << "interval " << k;
    // The sample std is the noise: within 20 % for hundreds of samples.
    EXPECT_NEAR(iv.std.x(), 0.02, 0.004);
    EXPECT_DOUBLE_EQ(iv.start_s, m.recording.time_s[iv.begin]);
    EXPECT_DOUBLE_EQ(iv.end_s, m.recording.time_s[iv.end - 1]);
  }
  // Quiet level: the statistic of pure noise is √3 σ.
  EXPECT_NEAR(r.quiet_level, std::sqrt(3.0) * 0.02, 0.2 * std::sqrt(3.0) * 0.02);
  EXPECT_DOUBLE_EQ(r.threshold, 3.0 * r.quiet_level);
  EXPECT_EQ(r.merged, 0);
  EXPECT_EQ(r.window_samples, 101u);
  EXPECT_EQ(r.finding.kind, DetectOutcome::kFound);
}

TEST(DetectStatic, TrimsTheSettlingAtBothEnds) {
  const Made m = Maker{}.Make(CubeFaces(6.0));
  DetectOptions o;
  o.settle_s = 0.0;
  const DetectResult loose = DetectStatic(m.recording, o);
  o.settle_s = 1.0;
  const DetectResult tight = DetectStatic(m.recording, o);
  ASSERT_EQ(loose.intervals.size(), tight.intervals.size());
  for (std::size_t k = 0; k < loose.intervals.size(); ++k) {
    EXPECT_NEAR(tight.intervals[k].start_s - loose.intervals[k].start_s, 1.0, 0.011);
    EXPECT_NEAR(loose.intervals[k].end_s - tight.intervals[k].end_s, 1.0, 0.011);
  }
}

TEST(DetectStatic, GivesTheSameIntervalsInCountsGAndMps2) {
  Maker mk;
  const Made mps2 = mk.Make(CubeFaces(5.0));
  mk.scale = 1.0 / kStandardGravityMps2;
  const Made g = mk.Make(CubeFaces(5.0));
  mk.scale = 400.0;  // counts per m/s², quantised, offset as an unsigned ADC
  mk.offset = 32768;
  mk.round = true;
  const Made counts = mk.Make(CubeFaces(5.0));
  Recording rc = counts.recording;
  rc.units = AccelUnits::kCounts;
  const DetectResult a = DetectStatic(mps2.recording, {});
  const DetectResult b = DetectStatic(g.recording, {});
  const DetectResult c = DetectStatic(rc, {});
  ASSERT_EQ(a.intervals.size(), 6u);
  ASSERT_EQ(b.intervals.size(), 6u);
  ASSERT_EQ(c.intervals.size(), 6u);
  for (std::size_t k = 0; k < 6; ++k) {
    // Same noise realisation: same decisions up to a few samples at the ends.
    EXPECT_NEAR(double(b.intervals[k].begin), double(a.intervals[k].begin), 3);
    EXPECT_NEAR(double(c.intervals[k].begin), double(a.intervals[k].begin), 3);
    EXPECT_NEAR(double(c.intervals[k].end), double(a.intervals[k].end), 3);
    const double tol =
        kMeanTolSigmas * 400 * 0.02 / std::sqrt(double(c.intervals[k].samples()));
    EXPECT_LT((c.intervals[k].mean - counts.truth[k]).cwiseAbs().maxCoeff(), tol);
  }
  EXPECT_NEAR(c.quiet_level / 400.0, a.quiet_level, 0.1 * a.quiet_level);
  EXPECT_NEAR(
      c.gravity_units, 400 * kStandardGravityMps2, 0.01 * 400 * kStandardGravityMps2);
}

TEST(DetectStatic, MergesAShortBumpAtTheSameOrientation) {
  Maker mk;
  Made m = mk.Make({{Eigen::Vector3d::UnitZ(), 6.0},
                    {Eigen::Vector3d::UnitX(), 12.0},
                    {Eigen::Vector3d::UnitY(), 6.0}});
  // A knock of 0.2 s in the middle of the second position.
  const std::size_t mid = (m.still[1].first + m.still[1].second) / 2;
  for (std::size_t i = mid; i < mid + 20; ++i) {
    m.recording.accel[i] += Eigen::Vector3d(0.0, 3.0, -2.0);
  }
  const DetectResult r = DetectStatic(m.recording, {});
  ASSERT_EQ(r.intervals.size(), 3u);
  EXPECT_EQ(r.merged, 1);
  const StaticInterval& iv = r.intervals[1];
  EXPECT_GT(iv.excluded, 20u);  // the knock, half windows and settling
  EXPECT_LT(iv.begin, mid);
  EXPECT_GT(iv.end, mid + 20);
  // The knock stays out of the mean (it would move y by 3·20/1000 = 0.06).
  const double tol = kMeanTolSigmas * 0.02 / std::sqrt(double(iv.samples()));
  EXPECT_LT((iv.mean - m.truth[1]).cwiseAbs().maxCoeff(), tol);

  DetectOptions no_merge;
  no_merge.merge_gap_s = 0.0;
  const DetectResult split = DetectStatic(m.recording, no_merge);
  EXPECT_EQ(split.intervals.size(), 4u);
  EXPECT_EQ(split.merged, 0);
}

TEST(DetectStatic, MergesAPositionAcrossAGapInTheData) {
  // The logger drops 2 s in the middle of a 6 s position: neither piece is
  // long enough alone, but no samples is not motion.
  Maker mk;
  Made m = mk.Make({{Eigen::Vector3d::UnitZ(), 6.0},
                    {Eigen::Vector3d::UnitX(), 6.0},
                    {Eigen::Vector3d::UnitY(), 6.0}});
  const std::size_t mid = (m.still[1].first + m.still[1].second) / 2;
  const std::size_t dropped = 200;  // 2 s at 100 Hz
  for (std::size_t i = mid + dropped; i < m.recording.size(); ++i) {
    m.recording.time_s[i - dropped] = m.recording.time_s[i] + 2.0;
    m.recording.accel[i - dropped] = m.recording.accel[i];
  }
  m.recording.time_s.resize(m.recording.size() - dropped);
  m.recording.accel.resize(m.recording.time_s.size());
  const DetectResult r = DetectStatic(m.recording, {});
  ASSERT_EQ(r.intervals.size(), 3u);
  EXPECT_EQ(r.merged, 1);
  EXPECT_EQ(r.dropped_short, 0);
  const double tol = kMeanTolSigmas * 0.02 / std::sqrt(double(r.intervals[1].samples()));
  EXPECT_LT((r.intervals[1].mean - m.truth[1]).cwiseAbs().maxCoeff(), tol);
}

TEST(DetectStatic, TakesTheSampleRateFromTimestampsRoundedToTheMillisecond) {
  // 160 Hz logged in whole milliseconds: steps of 6 and 7 ms.
  Made m = Maker{.rate_hz = 160.0}.Make(CubeFaces(4.0));
  for (double& t : m.recording.time_s) t = std::round(t * 1e3) / 1e3;
  const DetectResult r = DetectStatic(m.recording, {});
  EXPECT_NEAR(1.0 / r.sample_period_s, 160.0, 0.5);
  EXPECT_EQ(r.intervals.size(), 6u);
}

TEST(DetectStatic, WarnsWhenEvenTheQuietestStretchesMoveMoreThanAStillSensor) {
  // A sensor waved about all the time (0.06 g of shake), with --max-still
  // raised so that its least-moving stretches pass as positions.
  Maker mk;
  mk.noise = 0.6;
  mk.shake_mps2 = 3.0;
  const Made m = mk.Make(CubeFaces(6.0));
  DetectOptions raised;
  raised.max_still_g = 0.5;
  const DetectResult r = DetectStatic(m.recording, raised);
  ASSERT_FALSE(r.intervals.empty());
  ASSERT_EQ(Words(r.notes).size(), 1u);
  EXPECT_THAT(Words(r.notes)[0],
              HasSubstr("more than a MEMS accelerometer held still shows"));
  // The same session with a quiet sensor: no warning.
  EXPECT_TRUE(DetectStatic(Maker{}.Make(CubeFaces(6.0)).recording, raised).notes.empty());
}

TEST(DetectStatic, KeepsApartNearbyOrientationsAfterAQuickTurn) {
  Maker mk;
  mk.turn_s = 0.5;
  mk.shake_mps2 = 0.5;
  const Eigen::Vector3d tilted(std::sin(0.35), 0.0, std::cos(0.35));  // 20 deg
  const Made m = mk.Make({{Eigen::Vector3d::UnitZ(), 5.0}, {tilted, 5.0}});
  const DetectResult r = DetectStatic(m.recording, {});
  ASSERT_EQ(r.intervals.size(), 2u);
  EXPECT_EQ(r.merged, 0);
}

TEST(DetectStatic, DropsAndCountsShortStillStretches) {
  const Made m = Maker{}.Make({{Eigen::Vector3d::UnitZ(), 6.0},
                               {Eigen::Vector3d::UnitX(), 1.5},
                               {-Eigen::Vector3d::UnitZ(), 6.0}});
  const DetectResult r = DetectStatic(m.recording, {});
  ASSERT_EQ(r.intervals.size(), 2u);
  EXPECT_EQ(r.dropped_short, 1);
  EXPECT_GE(r.intervals[1].begin, m.still[2].first);
}

TEST(DetectStatic, WorksOnARecordingThatIsMostlyMotion) {
  // Three 4 s positions joined by 12 s of vigorous turning: 75 % motion.
  Maker mk;
  mk.turn_s = 12.0;
  mk.shake_mps2 = 2.0;
  const Made m = mk.Make({{Eigen::Vector3d::UnitZ(), 4.0},
                          {Eigen::Vector3d::UnitX(), 4.0},
                          {Eigen::Vector3d(0, 1, 1), 4.0}});
  const DetectResult r = DetectStatic(m.recording, {});
  ExpectIntervalsMatch(r, m.still);
}

TEST(DetectStatic, RejectsAnEmptyRecording) {
  Recording empty;
  empty.source = "empty.csv";
  try {
    DetectStatic(empty, {});
    FAIL() << "no throw";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("empty.csv"));
    EXPECT_THAT(e.what(), HasSubstr("empty"));
  }
}

TEST(DetectStatic, RejectsARecordingShorterThanAWindow) {
  Recording r;
  for (int i = 0; i < 50; ++i) {
    r.time_s.push_back(i * 0.01);
    r.accel.emplace_back(0, 0, kStandardGravityMps2);
  }
  try {
    DetectStatic(r, {});
    FAIL() << "no throw";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("shorter than one detection window"));
    EXPECT_EQ(e.kind(), ErrorKind::kSession);
    EXPECT_TRUE(Names(e.advice(), Option::kDetectWindow));
  }
}

TEST(DetectStatic, RejectsTimeThatGoesBackAndNonFiniteReadings) {
  Made m = Maker{}.Make(CubeFaces(3.0));
  Recording back = m.recording;
  back.time_s[500] = back.time_s[499];
  EXPECT_THROW(DetectStatic(back, {}), Error);
  Recording nan = m.recording;
  nan.accel[700].y() = std::numeric_limits<double>::quiet_NaN();
  try {
    DetectStatic(nan, {});
    FAIL() << "no throw";
  } catch (const NotFiniteError& e) {
    EXPECT_THAT(e.what(), HasSubstr("sample 700 is not finite: its accelerometer"));
    EXPECT_EQ(e.column(), RowColumn::kAccel);
    EXPECT_EQ(e.row(), 700u);
  }
}

TEST(DetectStatic, RefusesANonFiniteTimeInAViewOfTheCallersMemory) {
  // Rows no log reader checked, read in place (as the Python module hands
  // them over): the first pass refuses the infinite time, naming its row.
  const Made m = Maker{}.Make(CubeFaces(3.0));
  std::vector<double> t = m.recording.time_s;
  t[2000] = std::numeric_limits<double>::infinity();
  RecordingView view = m.recording;
  view.time_s = t;
  try {
    DetectStatic(view, {});
    FAIL() << "no throw";
  } catch (const NotFiniteError& e) {
    EXPECT_EQ(e.column(), RowColumn::kTime);
    EXPECT_EQ(e.row(), 2000u);
  }
}

TEST(DetectStatic, FindsNothingInARecordingThatNeverStopsMovingAndSaysWhy) {
  // A sensor tumbling slowly and continuously (30 deg/s) for a minute.
  Recording r;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> gauss(0.0, 0.02);
  for (int i = 0; i < 6000; ++i) {
    const double t = i / 100.0;
    const double a = 0.52 * t;
    const double b = 0.31 * t;
    r.time_s.push_back(t);
    r.accel.push_back(kStandardGravityMps2 * Eigen::Vector3d(std::cos(a) * std::sin(b),
                                                             std::sin(a) * std::sin(b),
                                                             std::cos(b)) +
                      Eigen::Vector3d(gauss(rng), gauss(rng), gauss(rng)));
  }
  const DetectResult res = DetectStatic(r, {});
  EXPECT_TRUE(res.intervals.empty());
  EXPECT_TRUE(res.threshold_capped);
  EXPECT_NEAR(res.threshold, 0.05 * kStandardGravityMps2, 1e-12);
  EXPECT_EQ(res.finding.kind, DetectOutcome::kNeverStill);
  EXPECT_THAT(Describe(res.finding), HasSubstr("never stops moving"));
  EXPECT_TRUE(Names(res.finding.advice, Option::kDetectMaxStill));
}

TEST(DetectStatic, ExplainsPositionsTooShortForTheMinimum) {
  Maker mk;
  std::vector<std::pair<Eigen::Vector3d, double>> quick;
  for (const auto& [d, s] : CubeFaces(2.0)) quick.emplace_back(d, 1.5);
  const Made m = mk.Make(quick);
  const DetectResult r = DetectStatic(m.recording, {});
  EXPECT_TRUE(r.intervals.empty());
  EXPECT_EQ(r.dropped_short, 6);
  // A 1.5 s position loses half a window at each end to the statistic (the
  // slow ends of the turns give a little back).
  EXPECT_GT(r.longest_still_s, 0.4);
  EXPECT_LT(r.longest_still_s, 1.0);
  EXPECT_EQ(r.finding.kind, DetectOutcome::kTooShort);
  EXPECT_THAT(Describe(r.finding), HasSubstr("longest still stretch lasts"));
  EXPECT_TRUE(Names(r.finding.advice, Option::kDetectMinStatic));
  // Following the advice finds them.
  DetectOptions o;
  o.window_s = 0.5;
  o.min_static_s = 0.5;
  EXPECT_EQ(DetectStatic(m.recording, o).intervals.size(), 6u);
}

TEST(DetectStatic, HandlesAConstantSignal) {
  Recording r;
  for (int i = 0; i < 1000; ++i) {
    r.time_s.push_back(i * 0.01);
    r.accel.emplace_back(33000, 32768, 36800);
  }
  r.units = AccelUnits::kCounts;
  const DetectResult res = DetectStatic(r, {});
  EXPECT_EQ(res.quiet_level, 0.0);
  EXPECT_EQ(res.threshold, 0.0);
  ASSERT_EQ(res.intervals.size(), 1u);
  EXPECT_EQ(res.intervals[0].mean, Eigen::Vector3d(33000, 32768, 36800));
  EXPECT_EQ(res.intervals[0].std, Eigen::Vector3d::Zero());
  // Everything but half a window and the settling at each end.
  EXPECT_NEAR(res.intervals[0].duration_s(), 10.0 - 2 * (0.5 + 0.3), 0.02);
}

TEST(DetectStatic, ToleratesACoarselyQuantisedSignal) {
  // Noise well below one count: most windows never change, some flicker.
  Maker mk;
  mk.noise = 0.0005;
  mk.scale = 400;
  mk.offset = 32768;
  mk.round = true;
  const Made m = mk.Make(CubeFaces(6.0));
  Recording r = m.recording;
  r.units = AccelUnits::kCounts;
  const DetectResult res = DetectStatic(r, {});
  EXPECT_NEAR(res.quiet_level, 0.5, 1e-12);  // half a count
  ExpectIntervalsMatch(res, m.still);
}

TEST(DetectStatic, FindsASingleLongRest) {
  const Made m = Maker{}.Make({{Eigen::Vector3d(0.1, -0.2, 1.0), 300.0}});
  const DetectResult r = DetectStatic(m.recording, {});
  ASSERT_EQ(r.intervals.size(), 1u);
  EXPECT_NEAR(r.intervals[0].duration_s(), 300.0 - 1.6, 0.02);
  EXPECT_EQ(r.dropped_short, 0);
}

// Sessions from the simulator: every position found, no turn sample inside
// an interval, means within noise of the truth.
class DetectSimulated
    : public ::testing::TestWithParam<std::pair<std::string, AccelUnits>> {};

TEST_P(DetectSimulated, FindsEverySimulatedPosition) {
  SimulateStaticOptions so;
  so.device = FindPreset(GetParam().first);
  so.units = GetParam().second;
  so.dwell_s = 6.0;
  so.initial_rest_s = 5.0;
  so.seed = 11;
  const SimulatedSession s = SimulateStatic(so);
  const DetectResult r = DetectStatic(s.recording, {});
  // The initial rest comes first, then the 26 positions.
  ASSERT_EQ(r.intervals.size(), s.still_ranges.size() + 1) << Describe(r.finding);
  EXPECT_LT(r.intervals[0].end, s.still_ranges[0].first);
  const std::vector<StaticInterval> positions(r.intervals.begin() + 1, r.intervals.end());
  const double per_unit = s.truth.mps2_per_unit;
  for (std::size_t k = 0; k < positions.size(); ++k) {
    const StaticInterval& iv = positions[k];
    EXPECT_GE(iv.begin, s.still_ranges[k].first) << "position " << k;
    EXPECT_LE(iv.end, s.still_ranges[k].second) << "position " << k;
    const Eigen::Vector3d truth_mps2 =
        s.truth.model.Forward(s.truth.gravity_mps2 * s.directions[k]);
    const double sigma =
        std::sqrt(s.noise_std_mps2.squaredNorm() / 3 +
                  s.quantisation_step_mps2 * s.quantisation_step_mps2 / 12);
    const double tol = kMeanTolSigmas * sigma / std::sqrt(double(iv.samples()));
    EXPECT_LT((iv.mean * per_unit - truth_mps2).cwiseAbs().maxCoeff(), tol)
        << "position " << k;
  }
}

INSTANTIATE_TEST_SUITE_P(
    Presets,
    DetectSimulated,
    ::testing::Values(std::make_pair(std::string("mti-g"), AccelUnits::kMps2),
                      std::make_pair(std::string("colibri"), AccelUnits::kG),
                      std::make_pair(std::string("inertiacube3"), AccelUnits::kMps2),
                      std::make_pair(std::string("mti-g"), AccelUnits::kCounts)),
    [](const ::testing::TestParamInfo<DetectSimulated::ParamType>& param_info) {
      std::string name =
          param_info.param.first + "_" + std::string(ToString(param_info.param.second));
      for (char& c : name) {
        if (c == '-') c = '_';
      }
      return name;
    });

// The real recordings (tests/data/real/).
TEST(DetectReal, XsensSessionHasTheInitialRestAndAbout37Positions) {
  LogOptions lo;
  lo.units = AccelUnits::kCounts;
  const Recording rec = ReadLog(RealDataPath("xsens-multiposition/xsens_acc.mat"), lo);
  const DetectResult r = DetectStatic(rec, {});
  ASSERT_GE(r.intervals.size(), 36u);
  EXPECT_LE(r.intervals.size(), 40u);
  // The initial rest: about 50 s from the start.
  EXPECT_LT(r.intervals[0].start_s - rec.time_s.front(), 2.0);
  EXPECT_GT(r.intervals[0].duration_s(), 45.0);
  for (std::size_t k = 0; k < r.intervals.size(); ++k) {
    const StaticInterval& iv = r.intervals[k];
    EXPECT_GE(iv.duration_s(), 2.0);
    // Held still: the noise of a position is that of the rest, not a turn's.
    EXPECT_LT(iv.noise(), 2.0 * r.intervals[0].noise()) << "interval " << k;
    if (k > 0) {
      // Neighbours are different positions (a turn separates them), about
      // 4000 counts per g: at least 10 degrees ≈ 700 counts apart.
      EXPECT_GT((iv.mean - r.intervals[k - 1].mean).norm(), 700.0) << "interval " << k;
    }
  }
}

TEST(DetectReal, FerrarisSessionCoversEveryPoseAndNoRotation) {
  LogOptions lo;
  lo.units = AccelUnits::kMps2;
  lo.time_unit = TimeUnit::kSampleIndex;
  lo.rate_hz = 102.4;
  const Recording rec =
      ReadLog(RealDataPath("imucal-ferraris/example_ferraris_session.csv"), lo);
  std::ifstream in(RealDataPath("imucal-ferraris/example_ferraris_session_list.json"));
  const nlohmann::json sections = nlohmann::json::parse(in);
  const DetectResult r = DetectStatic(rec, {});
  ASSERT_FALSE(r.intervals.empty());
  for (const char* pose : {"x_p", "x_a", "y_p", "y_a", "z_p", "z_a"}) {
    const std::size_t b = sections[pose]["start"];
    const std::size_t e = sections[pose]["end"];
    int overlapping = 0;
    for (const auto& iv : r.intervals) {
      if (iv.begin < e && iv.end > b) {
        ++overlapping;
        // Most of the labelled pose is inside the interval.
        const double covered = double(std::min(e, iv.end) - std::max(b, iv.begin));
        EXPECT_GT(covered, 0.8 * double(e - b)) << pose;
      }
    }
    EXPECT_EQ(overlapping, 1) << pose;
  }
  for (const char* rot : {"x_rot", "y_rot", "z_rot"}) {
    const std::size_t b = sections[rot]["start"];
    const std::size_t e = sections[rot]["end"];
    for (const auto& iv : r.intervals) {
      EXPECT_TRUE(iv.end <= b || iv.begin >= e)
          << rot << " [" << b << ", " << e << ") inside [" << iv.begin << ", " << iv.end
          << ")";
    }
  }
}

}  // namespace
}  // namespace mpcal
