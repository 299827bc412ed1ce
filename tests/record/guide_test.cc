// SessionGuide on simulated sessions fed as a live source feeds them: it
// captures the positions static detection finds on the same rows, says done
// once the positions' bound meets the target and not before, and points at
// directions not yet held; with a gyroscope, it knows which axes were turned.
#include <algorithm>
#include <cmath>
#include <cstddef>
#include <random>
#include <span>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "mpcal/coverage.h"
#include "mpcal/cramer_rao.h"
#include "mpcal/detect.h"
#include "mpcal/error.h"
#include "mpcal/record_guide.h"
#include "mpcal/simulate.h"
#include "record/guide_steps.h"

namespace mpcal {
namespace {

SimulatedSession Session(int positions, bool gyro, std::uint64_t seed = 7) {
  SimulateStaticOptions o;
  o.device = FindPreset("colibri");
  o.positions = positions;
  o.dwell_s = 6.0;
  o.turn_s = 2.5;
  o.initial_rest_s = 6.0;
  o.gyro = gyro;
  o.seed = seed;
  return SimulateStatic(o);
}

// Feeds the rows one at a time; returns every event and, after each one,
// the cube directions held at that moment.
struct Fed {
  std::vector<GuideEvent> events;
  std::vector<std::vector<bool>> held_before;
};

Fed FeedRowByRow(SessionGuide* guide, const Recording& r) {
  Fed fed;
  const bool gyro = !r.gyro_radps.empty();
  for (std::size_t i = 0; i < r.size(); ++i) {
    const std::vector<bool> held = guide->Held();
    const auto ev = guide->Feed(std::span(r.time_s).subspan(i, 1),
                                std::span(r.accel).subspan(i, 1),
                                gyro ? std::span(r.gyro_radps).subspan(i, 1)
                                     : std::span<const Eigen::Vector3d>{});
    for (const GuideEvent& e : ev) {
      fed.events.push_back(e);
      fed.held_before.push_back(held);
    }
  }
  return fed;
}

TEST(SessionGuide, CapturesThePositionsDetectionFinds) {
  const SimulatedSession s = Session(26, false);
  GuideOptions options;
  SessionGuide guide(options);
  FeedRowByRow(&guide, s.recording);
  const DetectResult d = DetectStatic(s.recording, options.detect);
  const auto& p = guide.Positions();
  ASSERT_EQ(p.size(), d.intervals.size());
  ASSERT_EQ(p.size(), 27u);  // the rest at the start and the 26
  for (std::size_t k = 0; k < p.size(); ++k) {
    // Within one window: the live threshold is of the statistics so far.
    EXPECT_NEAR(p[k].start_s, d.intervals[k].start_s, options.detect.window_s) << k;
    EXPECT_NEAR(p[k].end_s, d.intervals[k].end_s, options.detect.window_s) << k;
    // The means agree to well within the noise of one sample (0.03 m/s²).
    EXPECT_LT((p[k].mean_mps2 - d.intervals[k].mean).norm(), 0.01) << k;
  }
  // Each simulated position is held at the cube direction it was simulated
  // at (tilted by up to 5 deg, read through the sensor's errors).
  for (std::size_t k = 1; k < p.size(); ++k) {
    double off_deg = 0.0;
    EXPECT_EQ(p[k].nearest, internal::NearestCube(s.directions[k - 1], &off_deg)) << k;
    EXPECT_TRUE(p[k].holds_nearest) << k;
  }
}

TEST(SessionGuide, SameEventsHoweverTheRowsAreSplit) {
  const SimulatedSession s = Session(12, false);
  SessionGuide one(GuideOptions{});
  const Fed by_row = FeedRowByRow(&one, s.recording);
  SessionGuide pieces(GuideOptions{});
  std::mt19937 rng(3);
  std::vector<GuideEvent> events;
  const Recording& r = s.recording;
  for (std::size_t b = 0; b < r.size();) {
    const std::size_t n = std::min<std::size_t>(1 + rng() % 700, r.size() - b);
    const auto ev =
        pieces.Feed(std::span(r.time_s).subspan(b, n), std::span(r.accel).subspan(b, n));
    events.insert(events.end(), ev.begin(), ev.end());
    b += n;
  }
  ASSERT_EQ(events.size(), by_row.events.size());
  for (std::size_t i = 0; i < events.size(); ++i) {
    EXPECT_EQ(events[i].kind, by_row.events[i].kind);
    EXPECT_EQ(events[i].time_s, by_row.events[i].time_s);
    EXPECT_EQ(events[i].target, by_row.events[i].target);
  }
}

TEST(SessionGuide, DoneWhenTheBoundMeetsTheTargetAndNotBefore) {
  const SimulatedSession s = Session(26, false);
  GuideOptions options;
  SessionGuide guide(options);
  const Fed fed = FeedRowByRow(&guide, s.recording);
  const auto done =
      std::find_if(fed.events.begin(), fed.events.end(), [](const GuideEvent& e) {
        return e.kind == GuideEventKind::kDone;
      });
  ASSERT_NE(done, fed.events.end());
  const int n = done->positions;
  // Enough positions for 9 parameters, fewer than the whole cube.
  EXPECT_GE(n, 10);
  EXPECT_LT(n, 27);
  EXPECT_TRUE(done->bound.met());
  // No event before it saw the bound met.
  for (auto e = fed.events.begin(); e != done; ++e) EXPECT_FALSE(e->bound.met());

  // The bound again, by CramerRaoBound itself, on the positions at 'done'
  // (with the samples they had by the end) and on one position fewer.
  const auto& p = guide.Positions();
  const std::span<const GuidePosition> at_done(p.data(), static_cast<std::size_t>(n));
  const Eigen::Vector3d noise = internal::PooledNoise(at_done);
  // The noise pooled over the holds is the simulated sensor's white noise
  // and its quantisation (step²/12), within the spread of a standard
  // deviation over thousands of samples (2 %).
  for (int k = 0; k < 3; ++k) {
    const double expected =
        std::sqrt(s.noise_std_mps2[k] * s.noise_std_mps2[k] +
                  s.quantisation_step_mps2 * s.quantisation_step_mps2 / 12.0);
    EXPECT_NEAR(noise[k], expected, 0.04 * expected);
  }
  std::vector<BoundPosition> bp;
  for (const GuidePosition& q : at_done)
    bp.push_back({q.mean_mps2.normalized(), noise, q.samples, 0.0});
  const Eigen::Matrix<double, 9, 9> cov =
      CramerRaoBound(ErrorModel{}, bp, kStandardGravityMps2);
  for (int i = 0; i < 9; ++i) {
    EXPECT_LE(std::sqrt(cov(i, i)),
              done->bound.target[static_cast<std::size_t>(GroupOf(i))] * 1.0001)
        << i;
  }
  const GuideBound fewer =
      BoundOf(at_done.first(at_done.size() - 1), noise, done->bound.target, options);
  EXPECT_FALSE(fewer.met());
  EXPECT_TRUE(guide.Done());
}

TEST(SessionGuide, NextTargetIsADirectionNotYetHeld) {
  const SimulatedSession s = Session(20, false);
  SessionGuide guide(GuideOptions{});
  EXPECT_GE(guide.NextTarget(), 0);
  const Fed fed = FeedRowByRow(&guide, s.recording);
  int targets = 0;
  std::vector<bool> held(CanonicalDirections().size(), false);
  for (std::size_t i = 0; i < fed.events.size(); ++i) {
    const GuideEvent& e = fed.events[i];
    if (e.kind != GuideEventKind::kNextTarget) continue;
    ++targets;
    ASSERT_GE(e.target, 0);
    EXPECT_FALSE(guide.Positions().empty());
    // Not held by any position captured before the event.
    for (const GuidePosition& p : guide.Positions()) {
      if (p.start_s <= e.time_s && p.holds_nearest) {
        EXPECT_NE(p.nearest, e.target) << "at " << e.time_s;
      }
    }
  }
  EXPECT_GE(targets, 10);
}

TEST(SessionGuide, TargetsGivenAreUsed) {
  const SimulatedSession s = Session(26, false);
  GuideOptions options;
  options.target_bias_mps2 = 1e-6;  // beyond what these holds can reach
  options.target_scale = 1e-6;
  options.target_angle_rad = 1e-6;
  SessionGuide guide(options);
  const Fed fed = FeedRowByRow(&guide, s.recording);
  EXPECT_FALSE(guide.Done());
  EXPECT_EQ(guide.Bound().target[0], 1e-6);
  EXPECT_GT(guide.Bound().worst_ratio, 10.0);
}

TEST(SessionGuide, TheGyroscopeTurnsNamedByAxis) {
  // The rest (+z up), then the +x face: one turn of 90 deg about y.
  const SimulatedSession s = Session(1, true);
  SessionGuide guide(GuideOptions{});
  const Fed fed = FeedRowByRow(&guide, s.recording);
  ASSERT_EQ(guide.Positions().size(), 2u);
  const GuideTurns t = guide.Turns();
  EXPECT_TRUE(t.gyro);
  EXPECT_EQ(t.turns, 1);
  // The true rotation over the same rows, from the simulator's true rate
  // (body frame), integrated apart from the guide: the guide's turn (a
  // nominal gyroscope, its bias taken at the position before) agrees with
  // it within the gyroscope's errors (0.1 % of scale, mrad misalignments).
  const Recording& r = s.recording;
  Eigen::Quaterniond q = Eigen::Quaterniond::Identity();
  for (std::size_t i = 0; i + 1 < r.size(); ++i) {
    if (r.time_s[i] < guide.Positions()[0].end_s ||
        r.time_s[i + 1] > guide.Positions()[1].start_s) {
      continue;
    }
    const Eigen::Vector3d w = 0.5 * (s.true_rate_radps[i] + s.true_rate_radps[i + 1]);
    const double dt = r.time_s[i + 1] - r.time_s[i];
    const double angle = w.norm() * dt;
    if (angle > 0.0) q = q * Eigen::Quaterniond(Eigen::AngleAxisd(angle, w.normalized()));
  }
  const Eigen::AngleAxisd truth(q);
  const Eigen::Vector3d truth_deg =
      truth.axis() * truth.angle() * 180.0 / 3.141592653589793;
  for (int k = 0; k < 3; ++k) {
    EXPECT_NEAR(t.about_deg[static_cast<std::size_t>(k)], std::abs(truth_deg[k]), 1.5)
        << k;
  }
  // From lying flat to the +x face: mostly about y.
  EXPECT_GT(std::abs(truth_deg[1]), 60.0);
  EXPECT_TRUE(t.excited[1]);
  EXPECT_FALSE(t.all_excited());
  int needed = 0;
  for (const GuideEvent& e : fed.events) needed += e.kind == GuideEventKind::kTurnNeeded;
  EXPECT_GE(needed, 1);
  EXPECT_FALSE(t.all_excited());

  // The whole cube turns about every axis.
  const SimulatedSession full = Session(26, true);
  SessionGuide all(GuideOptions{});
  FeedRowByRow(&all, full.recording);
  EXPECT_TRUE(all.Turns().all_excited());
  EXPECT_TRUE(all.Done());
}

TEST(SessionGuide, BadOptionsAndRows) {
  GuideOptions o;
  o.near_deg = 0.0;
  EXPECT_THROW(SessionGuide{o}, Error);
  SessionGuide g(GuideOptions{});
  const std::vector<double> t = {0.0, 0.01};
  const std::vector<Eigen::Vector3d> a(1, Eigen::Vector3d(0, 0, 9.8));
  EXPECT_THROW(g.Feed(t, a), Error);
}

}  // namespace
}  // namespace mpcal
