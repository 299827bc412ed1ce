// The steps of SimulateWalk (walk.cc), private to the simulate room: the
// loop's corners, the timeline of rests, sides and turns, the walker's state
// at any time, and the sampling by the IMU and the GNSS receiver. Tests reach
// them through this header.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "mpcal/simulate_walk.h"
#include "simulate/random.h"

namespace mpcal::internal {

/// The walker's state at one instant, in east-north-up.
struct WalkState {
  Eigen::Vector3d position = Eigen::Vector3d::Zero();
  Eigen::Vector3d acceleration = Eigen::Vector3d::Zero();
  double heading_rad = 0.0;  // of the walker, counter-clockwise from east
  double heading_rate_radps = 0.0;
};

enum class PhaseKind { kStill, kSide, kTurn };

/// One part of the walk: a rest, a side of the loop (ramp up, cruise with
/// the steps' bob, ramp down) or a turn on the spot.
struct WalkPhase {
  PhaseKind kind = PhaseKind::kStill;
  double start_s = 0.0;
  double duration_s = 0.0;
  Eigen::Vector3d from = Eigen::Vector3d::Zero();
  Eigen::Vector3d along = Eigen::Vector3d::UnitX();  // unit, horizontal
  double length_m = 0.0;
  double cruise_s = 0.0;
  double step_radps = 0.0;  // angular frequency of the steps
  double heading_rad = 0.0;
  double turn_rad = 0.0;
};

/// The loop's corners, counter-clockwise from a random azimuth, each but the
/// first jittered by up to corner_jitter_m; the first repeated at the end.
std::vector<Eigen::Vector3d> LoopCorners(const SimulateWalkOptions& o,
                                         PortableRandom& shape);

/// The timeline: a rest, the four sides with a stop (and, turning, a turn
/// between two halves of the stop) at each corner, a rest. Each side's cruise
/// holds whole sway cycles, so that the bob ends where it started.
std::vector<WalkPhase> WalkTimeline(const SimulateWalkOptions& o,
                                    const std::vector<Eigen::Vector3d>& corners);

/// The walker's state at t_s within phase `p`.
WalkState Evaluate(const WalkPhase& p, double t_s, const SimulateWalkOptions& o);

/// The state at increasing times: walks the timeline forward (never back).
class WalkCursor {
 public:
  WalkCursor(const std::vector<WalkPhase>& phases, const SimulateWalkOptions& o)
      : phases_(phases), options_(o) {}
  WalkState At(double t_s);

 private:
  const std::vector<WalkPhase>& phases_;
  const SimulateWalkOptions& options_;
  std::size_t phase_ = 0;
};

}  // namespace mpcal::internal
