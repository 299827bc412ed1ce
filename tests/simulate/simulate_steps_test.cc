// The steps of SimulateStatic and SimulateWalk on their own
// (src/simulate/static_steps.h, walk_steps.h).
#include <cmath>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mpcal/error.h"
#include "mpcal/simulate.h"
#include "mpcal/simulate_walk.h"
#include "mpcal/units.h"
#include "simulate/static_steps.h"
#include "simulate/walk_steps.h"

namespace mpcal::internal {
namespace {

SimulateStaticOptions Static(AccelUnits units) {
  SimulateStaticOptions o;
  o.device = FindPreset("colibri");
  o.units = units;
  o.rate_hz = 100.0;
  o.initial_rest_s = 2.004;
  o.turn_s = 1.5;
  o.dwell_s = 3.0;
  o.positions = 4;
  return o;
}

TEST(PlanStaticSession, DurationsRoundToWholeSamples) {
  const StaticPlan plan = PlanStaticSession(Static(AccelUnits::kMps2));
  EXPECT_EQ(plan.rest_n, 200u);
  EXPECT_EQ(plan.turn_n, 150u);
  EXPECT_EQ(plan.dwell_n, 300u);
  EXPECT_EQ(plan.total, 200u + 4u * 450u);
  // Rate 0: the device's.
  SimulateStaticOptions device_rate = Static(AccelUnits::kMps2);
  device_rate.rate_hz = 0.0;
  EXPECT_EQ(PlanStaticSession(device_rate).rate_hz, device_rate.device.rate_hz);
}

TEST(DrawStaticGeometry, DwellsFollowTheirTurnsAndTheStateIsStillThere) {
  const SimulateStaticOptions o = Static(AccelUnits::kMps2);
  const StaticPlan plan = PlanStaticSession(o);
  const StaticGeometry g = DrawStaticGeometry(o, plan);
  ASSERT_EQ(g.turns.size(), 4u);
  ASSERT_EQ(g.still_ranges.size(), 4u);
  EXPECT_EQ(g.still_ranges[0].first, 350u);
  EXPECT_EQ(g.still_ranges[3].second, plan.total);
  // In a dwell: the turn's end orientation, no acceleration; each position's
  // "up" seen from the sensor is its direction.
  for (std::size_t k = 0; k < 4; ++k) {
    Eigen::Quaterniond q;
    Eigen::Vector3d a;
    g.StateAt(static_cast<double>(g.still_ranges[k].first + 10) / plan.rate_hz, q, a);
    EXPECT_EQ(a, Eigen::Vector3d::Zero());
    const Eigen::Vector3d up_in_sensor = q.conjugate() * Eigen::Vector3d::UnitZ();
    EXPECT_NEAR((up_in_sensor - g.directions[k]).norm(), 0.0, 1e-12) << k;
  }
  // The same seed, the same geometry.
  EXPECT_EQ(DrawStaticGeometry(o, plan).directions[2], g.directions[2]);
}

TEST(DigitiseAccel, ResolutionRangeAndUnits) {
  SimulateStaticOptions o = Static(AccelUnits::kCounts);
  DevicePreset device = o.device;
  device.resolution_mps2 = 0.01;
  device.range_mps2 = 20.0;
  o.counts_offset = 100.0;
  o.counts_per_mps2 = 10.0;
  const Eigen::Vector3d y = DigitiseAccel({1.234, -30.0, 9.806}, device, o);
  // 1.23 m/s² → 112.3 → 112; clipped to -20 → -100; 9.81 → 198.1 → 198.
  EXPECT_EQ(y, Eigen::Vector3d(112.0, -100.0, 198.0));
  o.units = AccelUnits::kG;
  EXPECT_NEAR(DigitiseAccel({0, 0, kStandardGravityMps2}, device, o).z(),
              9.81 / kStandardGravityMps2,
              1e-12);
}

TEST(StaticTruth, CorrectsACountsReadingBackToTheForce) {
  SimulateStaticOptions o = Static(AccelUnits::kCounts);
  o.counts_offset = 512.0;
  o.counts_per_mps2 = 400.0;
  const Calibration truth = StaticTruth(o, PlanStaticSession(o), 9.81);
  const Eigen::Vector3d f(1.0, -2.0, 9.5);
  const Eigen::Vector3d reading =
      Eigen::Vector3d::Constant(o.counts_offset) + o.device.truth.Forward(f) * 400.0;
  EXPECT_NEAR((truth.Correct(reading) - f).norm(), 0.0, 1e-9);
}

SimulateWalkOptions Walk(bool turn) {
  SimulateWalkOptions o;
  o.device = FindPreset("mti-g");
  o.turn = turn;
  return o;
}

TEST(LoopCorners, ClosedLoopOfTheAskedSides) {
  SimulateWalkOptions o = Walk(false);
  o.corner_jitter_m = 0.0;
  PortableRandom shape(3);
  const std::vector<Eigen::Vector3d> c = LoopCorners(o, shape);
  ASSERT_EQ(c.size(), 5u);
  EXPECT_EQ(c.front(), c.back());
  EXPECT_NEAR((c[1] - c[0]).norm(), o.length_m, 1e-9);
  EXPECT_NEAR((c[2] - c[1]).norm(), o.width_m, 1e-9);
}

TEST(WalkTimeline, SidesHoldWholeSwayCyclesAndTurnsSplitTheStops) {
  for (const bool turn : {false, true}) {
    const SimulateWalkOptions o = Walk(turn);
    PortableRandom shape(5);
    const std::vector<WalkPhase> phases = WalkTimeline(o, LoopCorners(o, shape));
    // rest, 4 sides, 3 corners (1 or 3 phases each), rest.
    EXPECT_EQ(phases.size(), turn ? 15u : 9u);
    for (std::size_t i = 1; i < phases.size(); ++i) {
      EXPECT_DOUBLE_EQ(phases[i].start_s,
                       phases[i - 1].start_s + phases[i - 1].duration_s);
    }
    for (const WalkPhase& p : phases) {
      if (p.kind != PhaseKind::kSide) continue;
      const double cycles = p.step_radps * p.cruise_s / (4.0 * M_PI);
      EXPECT_NEAR(cycles, std::round(cycles), 1e-9);
      // The walker ends the side at its far corner, at rest.
      const WalkState end = Evaluate(p, p.start_s + p.duration_s, o);
      EXPECT_NEAR((end.position - (p.from + p.length_m * p.along)).norm(), 0.0, 1e-9);
    }
  }
}

TEST(SimulatePreconditions, ANegativeRateIsAnOptionError) {
  SimulateStaticOptions o = Static(AccelUnits::kMps2);
  o.rate_hz = -100.0;
  try {
    SimulateStatic(o);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kOption);
    EXPECT_THAT(e.what(), ::testing::HasSubstr("rate_hz"));
  }
  SimulateWalkOptions w = Walk(false);
  w.rate_hz = -1.0;
  try {
    SimulateWalk(w);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kOption);
  }
}

}  // namespace
}  // namespace mpcal::internal
