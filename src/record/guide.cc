// The session guide: rows in, the still runs of static detection's rule
// found as they arrive, positions captured at the minimum hold, and after
// each the bound, the next direction and the turns (record_guide.h).
#include <algorithm>
#include <cmath>
#include <deque>
#include <numbers>
#include <utility>

#include <fmt/format.h>

#include "guide_steps.h"
#include "mpcal/coverage.h"
#include "mpcal/error.h"
#include "mpcal/record_guide.h"
#include "mpcal/still_windows.h"

namespace mpcal {
namespace {

constexpr double kRadToDeg = 180.0 / std::numbers::pi;
// Rows the still window is sized from: a few seconds at any usual rate.
constexpr std::size_t kPeriodRows = 256;
// The gyroscope's rows kept for a turn (s): a longer turn is not counted.
constexpr double kKeepTurnS = 120.0;

}  // namespace

struct SessionGuide::State {
  // One row kept: its time, reading, gyroscope, and the time missing before
  // it (steps longer than the window: no samples, not motion).
  struct Row {
    double t = 0.0;
    Eigen::Vector3d a = Eigen::Vector3d::Zero();
    Eigen::Vector3d g = Eigen::Vector3d::Zero();
    double missing_before_s = 0.0;
  };

  // Sums of the samples of one position (readings about its first).
  struct Sums {
    Eigen::Vector3d ref = Eigen::Vector3d::Zero();
    Eigen::Vector3d s1 = Eigen::Vector3d::Zero();
    Eigen::Vector3d s2 = Eigen::Vector3d::Zero();
    Eigen::Vector3d g1 = Eigen::Vector3d::Zero();
    std::size_t n = 0;

    void Add(const Eigen::Vector3d& a, const Eigen::Vector3d& g) {
      if (n == 0) ref = a;
      const Eigen::Vector3d d = a - ref;
      s1 += d;
      s2 += d.cwiseAbs2();
      g1 += g;
      ++n;
    }
    Eigen::Vector3d Mean() const { return ref + s1 / static_cast<double>(n); }
    Eigen::Vector3d Std() const {
      if (n < 2) return Eigen::Vector3d::Zero();
      const double nn = static_cast<double>(n);
      return ((s2 - s1.cwiseAbs2() / nn) / (nn - 1.0)).cwiseMax(0.0).cwiseSqrt();
    }
  };

  GuideOptions options;
  StillWindows monitor;
  std::vector<StillWindow> judged;
  bool gyro = false;
  std::size_t rows = 0;

  // Rows kept for the gravity now (the last window) and for the turns.
  std::deque<Row> kept;
  std::size_t kept_base = 0;  // row index of kept.front()
  double missing_s = 0.0;     // time missing so far
  Eigen::Vector3d recent_sum = Eigen::Vector3d::Zero();
  std::size_t recent_count = 0;  // rows of kept in the last window
  std::size_t recent_first = 0;  // row index of the first of them

  // The threshold, refreshed every window_s of log time.
  double threshold = 0.0;
  bool threshold_known = false;
  double next_refresh_s = 0.0;

  // The latest window and the still run it belongs to.
  StillWindow latest;
  bool any_window = false;
  bool in_run = false;
  double run_start_s = 0.0;
  std::deque<StillWindow> pending;  // still, within settle_s of the latest

  // The group being built (pieces merged across bumps), as a position.
  bool open = false;
  bool captured = false;
  bool piece_open = false;
  Sums sums;
  GuidePosition building;
  double group_first_s = 0.0;
  double last_commit_missing_s = 0.0;

  std::vector<GuidePosition> positions;
  std::vector<bool> held;
  GuideBound bound;
  int next_target = -1;
  bool done = false;
  // The turns: their rotation vectors (rad).
  std::vector<Eigen::Vector3d> turns;

  explicit State(const GuideOptions& o)
      : options(o),
        monitor(o.detect, AccelUnits::kMps2, kPeriodRows),
        held(CanonicalDirections().size(), false) {}

  void TakeRow(double t, const Eigen::Vector3d& a, const Eigen::Vector3d& g);
  void Judge(const StillWindow& w, std::vector<GuideEvent>* events);
  void EndRun(std::vector<GuideEvent>* events);
  void Commit(const StillWindow& w, std::vector<GuideEvent>* events);
  void StartPiece(const StillWindow& w);
  void Capture(double at_s, std::vector<GuideEvent>* events);
  void Assess(double at_s, bool captured_now, std::vector<GuideEvent>* events);
  void AddTurn();
  GuideTurns TurnsNow() const;
  const Row* RowAt(std::size_t index) const {
    if (index < kept_base || index - kept_base >= kept.size()) return nullptr;
    return &kept[index - kept_base];
  }
};

void SessionGuide::State::TakeRow(double t,
                                  const Eigen::Vector3d& a,
                                  const Eigen::Vector3d& g) {
  if (!kept.empty() && t - kept.back().t > options.detect.window_s) {
    missing_s += t - kept.back().t;
  }
  kept.push_back({t, a, g, missing_s});
  ++rows;
  recent_sum += a;
  ++recent_count;
  // (The rows from recent_first on are always kept.)
  while (recent_count > 1 &&
         t - kept[recent_first - kept_base].t > options.detect.window_s) {
    recent_sum -= kept[recent_first - kept_base].a;
    ++recent_first;
    --recent_count;
  }
  // Keep the last window, the rows whose windows are not yet judged or
  // committed, and the turn since the last position (up to kKeepTurnS).
  std::size_t protect = 0;
  if (any_window) {
    protect = std::min(recent_first, pending.empty() ? latest.row : pending.front().row);
  }
  const double keep_from_s =
      positions.empty() ? t : std::max(positions.back().end_s, t - kKeepTurnS);
  while (kept.size() > 1 && kept_base < protect && kept.front().t < keep_from_s) {
    kept.pop_front();
    ++kept_base;
  }
}

void SessionGuide::State::Judge(const StillWindow& w, std::vector<GuideEvent>* events) {
  if (!threshold_known || w.centre_s >= next_refresh_s) {
    threshold = monitor.Verdict().threshold;
    threshold_known = true;
    next_refresh_s = w.centre_s + options.detect.window_s;
  }
  const bool still = w.statistic <= threshold;
  const bool gap = any_window && w.centre_s - latest.centre_s > options.detect.window_s;
  if (in_run && (!still || gap)) EndRun(events);
  latest = w;
  any_window = true;
  if (!still) return;
  if (!in_run) {
    in_run = true;
    run_start_s = w.centre_s;
    pending.clear();
  }
  pending.push_back(w);
  while (!pending.empty() &&
         pending.front().centre_s <= w.centre_s - options.detect.settle_s) {
    const StillWindow c = pending.front();
    pending.pop_front();
    if (c.centre_s >= run_start_s + options.detect.settle_s) Commit(c, events);
  }
}

void SessionGuide::State::EndRun(std::vector<GuideEvent>* events) {
  in_run = false;
  pending.clear();  // the settling at the end
  if (piece_open) {
    piece_open = false;
    // The position as held to the end: judged again with all its samples.
    if (captured) Assess(building.end_s, false, events);
  }
}

void SessionGuide::State::StartPiece(const StillWindow& w) {
  piece_open = true;
  const DetectOptions& d = options.detect;
  if (open) {
    // DetectStatic's merge across a bump: the time with samples between the
    // pieces, less the settling on both sides and the window's smear, and
    // the angle between the position and this first reading.
    const Row* r = RowAt(w.row);
    const double missing =
        r != nullptr ? r->missing_before_s - last_commit_missing_s : 0.0;
    const double bump_s =
        w.centre_s - building.end_s - missing - 2.0 * d.settle_s - d.window_s;
    if (bump_s < d.merge_gap_s &&
        internal::AngleDeg(sums.Mean(), w.reading) < d.merge_angle_deg) {
      return;
    }
  }
  // A new group; the one before, never held long enough, is dropped.
  open = true;
  captured = false;
  sums = Sums{};
  building = GuidePosition{};
  building.start_s = w.centre_s;
  group_first_s = w.centre_s;
}

void SessionGuide::State::Commit(const StillWindow& w, std::vector<GuideEvent>* events) {
  if (!piece_open) StartPiece(w);
  const Row* r = RowAt(w.row);
  sums.Add(w.reading, gyro && r != nullptr ? r->g : Eigen::Vector3d::Zero());
  if (r != nullptr) last_commit_missing_s = r->missing_before_s;
  building.end_s = w.centre_s;
  building.mean_mps2 = sums.Mean();
  building.std_mps2 = sums.Std();
  building.samples = sums.n;
  building.gyro_mean_radps = sums.g1 / static_cast<double>(sums.n);
  building.nearest =
      internal::NearestCube(building.mean_mps2.normalized(), &building.off_deg);
  building.holds_nearest = building.off_deg <= options.near_deg;
  if (captured) {
    positions.back() = building;
  } else if (w.centre_s - group_first_s >= options.detect.min_static_s) {
    Capture(w.centre_s, events);
  }
}

void SessionGuide::State::Capture(double at_s, std::vector<GuideEvent>* events) {
  captured = true;
  positions.push_back(building);
  if (gyro && positions.size() >= 2) AddTurn();
  GuideEvent e;
  e.kind = GuideEventKind::kCaptured;
  e.time_s = at_s;
  e.positions = static_cast<int>(positions.size());
  e.direction = building.nearest;
  e.off_deg = building.off_deg;
  events->push_back(e);
  Assess(at_s, true, events);
}

GuideTurns SessionGuide::State::TurnsNow() const {
  GuideTurns t;
  t.gyro = gyro;
  t.turns = static_cast<int>(turns.size());
  for (int k = 0; k < 3; ++k) {
    double sq = 0.0;
    for (const Eigen::Vector3d& r : turns) sq += r[k] * r[k];
    t.about_deg[static_cast<std::size_t>(k)] = std::sqrt(sq) * kRadToDeg;
    t.excited[static_cast<std::size_t>(k)] =
        t.about_deg[static_cast<std::size_t>(k)] >= options.min_turn_deg;
  }
  return t;
}

// The bound, the targets, the next direction, done, and the turn still
// needed, after a capture (events for all) or at the end of a position's
// hold (an event only when done or the next direction changed).
void SessionGuide::State::Assess(double at_s,
                                 bool captured_now,
                                 std::vector<GuideEvent>* events) {
  std::fill(held.begin(), held.end(), false);
  for (const GuidePosition& p : positions) {
    if (p.holds_nearest) held[static_cast<std::size_t>(p.nearest)] = true;
  }
  const Eigen::Vector3d noise = internal::PooledNoise(positions);
  const auto target =
      internal::Targets(noise, internal::MedianSamples(positions), options);
  bound = BoundOf(positions, noise, target, options);
  const GuideTurns t = TurnsNow();
  const bool was_done = done;
  done = done || (bound.met() && (!gyro || t.all_excited()));
  const int before = next_target;
  next_target =
      bound.met() ? -1 : internal::NextTargetOf(positions, held, noise, target, options);
  GuideEvent e;
  e.time_s = at_s;
  e.positions = static_cast<int>(positions.size());
  e.bound = bound;
  if (done) {
    if (!was_done) {
      e.kind = GuideEventKind::kDone;
      events->push_back(e);
    }
    return;
  }
  if (next_target >= 0 && (captured_now || next_target != before)) {
    e.kind = GuideEventKind::kNextTarget;
    e.target = next_target;
    events->push_back(e);
  }
  if (gyro && captured_now && positions.size() >= 2 && !t.all_excited()) {
    e.kind = GuideEventKind::kTurnNeeded;
    e.target = -1;
    e.axis = !t.excited[0] ? 0 : (!t.excited[1] ? 1 : 2);
    events->push_back(e);
  }
}

// The turn from the end of the position before the last to the start of
// the last, when its rows are still kept.
void SessionGuide::State::AddTurn() {
  const GuidePosition& from = positions[positions.size() - 2];
  const GuidePosition& to = positions.back();
  std::vector<double> t;
  std::vector<Eigen::Vector3d> g;
  if (kept.empty() || kept.front().t > from.end_s) return;
  for (const Row& r : kept) {
    if (r.t < from.end_s) continue;
    if (r.t > to.start_s) break;
    t.push_back(r.t);
    g.push_back(r.g);
  }
  turns.push_back(internal::TurnRotation(t, g, from.gyro_mean_radps));
}

SessionGuide::SessionGuide(const GuideOptions& options) {
  if (const std::string bad = options.Validate(); !bad.empty()) {
    throw Error(ErrorKind::kOption, "session guide options: " + bad);
  }
  state_ = std::make_unique<State>(options);
  State& s = *state_;
  s.next_target = internal::NextTargetOf(
      s.positions, s.held, Eigen::Vector3d::Zero(), {1.0, 1.0, 1.0}, options);
}

SessionGuide::~SessionGuide() = default;
SessionGuide::SessionGuide(SessionGuide&&) noexcept = default;
SessionGuide& SessionGuide::operator=(SessionGuide&&) noexcept = default;

std::vector<GuideEvent> SessionGuide::Feed(std::span<const double> time_s,
                                           std::span<const Eigen::Vector3d> accel_mps2,
                                           std::span<const Eigen::Vector3d> gyro_radps) {
  State& s = *state_;
  const bool has_gyro = !gyro_radps.empty();
  if (accel_mps2.size() != time_s.size() ||
      (has_gyro && gyro_radps.size() != time_s.size())) {
    throw Error(ErrorKind::kInput,
                fmt::format("session guide: {} times, {} accelerometer and {} gyroscope "
                            "readings",
                            time_s.size(),
                            accel_mps2.size(),
                            gyro_radps.size()));
  }
  if (time_s.empty()) return {};
  if (s.rows > 0 && has_gyro != s.gyro) {
    throw Error(ErrorKind::kInput, "session guide: rows with and without a gyroscope");
  }
  s.gyro = has_gyro;
  std::vector<GuideEvent> events;
  for (std::size_t i = 0; i < time_s.size(); ++i) {
    if (!std::isfinite(time_s[i]) || !accel_mps2[i].allFinite() ||
        (has_gyro && !gyro_radps[i].allFinite())) {
      throw Error(
          ErrorKind::kInput,
          fmt::format("session guide: a value that is not a number at {} s", time_s[i]));
    }
    // One row at a time: the threshold is refreshed at the same windows
    // however the rows are split.
    s.judged.clear();
    s.monitor.Add(time_s.subspan(i, 1), accel_mps2.subspan(i, 1), &s.judged);
    s.TakeRow(
        time_s[i], accel_mps2[i], has_gyro ? gyro_radps[i] : Eigen::Vector3d::Zero());
    for (const StillWindow& w : s.judged) s.Judge(w, &events);
  }
  return events;
}

GravityNow SessionGuide::Gravity() const {
  const State& s = *state_;
  GravityNow g;
  if (s.recent_count == 0 || s.recent_sum.norm() == 0.0) return g;
  g.known = true;
  g.direction = s.recent_sum.normalized();
  g.nearest = internal::NearestCube(g.direction, &g.off_deg);
  return g;
}

StillMeter SessionGuide::Meter() const {
  const State& s = *state_;
  StillMeter m;
  if (!s.any_window) return m;
  m.known = true;
  m.statistic_mps2 = s.latest.statistic;
  m.threshold_mps2 = s.threshold;
  m.still = s.in_run;
  if (!s.in_run) return m;
  m.held_s = s.latest.centre_s - s.run_start_s;
  if (s.captured && s.piece_open) {
    m.progress = 1.0;
  } else {
    const double need = s.options.detect.min_static_s + 2.0 * s.options.detect.settle_s;
    m.progress = std::clamp(m.held_s / need, 0.0, 1.0);
  }
  return m;
}

const std::vector<GuidePosition>& SessionGuide::Positions() const {
  return state_->positions;
}
std::vector<bool> SessionGuide::Held() const { return state_->held; }
int SessionGuide::NextTarget() const { return state_->next_target; }
GuideBound SessionGuide::Bound() const { return state_->bound; }
GuideTurns SessionGuide::Turns() const { return state_->TurnsNow(); }
bool SessionGuide::Done() const { return state_->done; }

}  // namespace mpcal
