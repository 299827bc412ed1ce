// Whether a record is still throughout, decided as its rows arrive, by
// static detection's rule (detect.cc), in memory that does not grow with the
// record: the rows of one window and a bounded sample of the statistics.
#include <algorithm>
#include <cmath>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "detect_steps.h"
#include "motion_statistic.h"
#include "mpcal/detect.h"
#include "mpcal/error.h"
#include "mpcal/still_windows.h"
#include "mpcal/systematic_sample.h"
#include "mpcal/units.h"

namespace mpcal {
namespace {

// Rows taken into the buffer at a time, and rows dropped from its front at
// once: the buffer stays under a window plus twice this.
constexpr std::size_t kSliceRows = 8192;
// Most statistics kept for the quiet level (1 MB).
constexpr std::size_t kMaxKept = std::size_t{1} << 17;
// Named as DetectStatic names a recording without a source.
constexpr const char* kSource = "recording";
// Rows the sample period (and so the window) is taken from, by default.
constexpr std::size_t kPeriodRows = 4096;

}  // namespace

namespace internal {

// The rule's state, shared by StillnessMonitor (the verdict) and
// StillWindows (every window as it is judged).
struct MonitorCore {
  DetectOptions options;
  std::size_t period_rows = kPeriodRows;
  // Where the windows judged go (StillWindows), or nowhere.
  std::vector<StillWindow>* judged = nullptr;
  bool counts = false;
  double one_g = 0.0;        // one g in the recording's units
  double range_limit = 0.0;  // |a_k| at or beyond this: at the range limit

  // Row by row: the last row, the reading step, the first reason found.
  std::size_t rows = 0;
  double last_t = 0.0;
  Eigen::Vector3d last_a = Eigen::Vector3d::Zero();
  double step = std::numeric_limits<double>::infinity();
  NotStillReason event = NotStillReason::kNone;
  double event_at_s = 0.0;
  bool stopped = false;  // a non-finite value: later rows are ignored

  // The window (half == 0 until sized) and the rows not yet dropped:
  // t[i], a[i] is row base + i.
  std::size_t half = 0;
  double period_s = 0.0;
  Eigen::Vector3d ref = Eigen::Vector3d::Zero();
  internal::WindowSums sums;
  std::vector<double> t;
  std::vector<Eigen::Vector3d> a;
  std::size_t base = 0;
  std::size_t next_centre = 0;  // row of the next window centre to judge

  // The statistics: how many, the largest, and a sample of them (the same
  // windows whatever the split).
  std::size_t windows = 0;
  double largest = 0.0;
  double largest_at_s = 0.0;
  SystematicSample kept{kMaxKept};

  void NoteEvent(NotStillReason reason, double at_s) {
    if (event != NotStillReason::kNone) return;
    event = reason;
    event_at_s = at_s;
  }

  // Checks one row and takes it into the buffer; false when it is not
  // finite (and the record ends there).
  bool TakeRow(double ti, const Eigen::Vector3d& ai) {
    if (!std::isfinite(ti) || !ai.allFinite()) {
      NoteEvent(NotStillReason::kNotFinite, last_t);
      stopped = true;
      return false;
    }
    if (rows > 0) {
      if (!(ti > last_t)) {
        throw Error(ErrorKind::kTime,
                    fmt::format("{}: time does not increase at sample {} ({} s after "
                                "{} s); the static detector needs a strictly "
                                "increasing time column",
                                kSource,
                                rows,
                                ti,
                                last_t));
      }
      if (ti - last_t > options.window_s) NoteEvent(NotStillReason::kGap, last_t);
      for (int k = 0; k < 3; ++k) {
        const double d = std::abs(ai[k] - last_a[k]);
        if (d > 0.0 && d < step) step = d;
      }
    }
    if (ai.cwiseAbs().maxCoeff() >= range_limit) {
      NoteEvent(NotStillReason::kRangeLimit, ti);
    }
    t.push_back(ti);
    a.push_back(ai);
    last_t = ti;
    last_a = ai;
    ++rows;
    return true;
  }

  // Whether rows t, a (after the last row) are all finite, in time order,
  // within the range and the window of each other: then TakeRows takes them
  // at once. Tests combined without a branch per row, so that it vectorises.
  bool Plain(std::span<const double> ts, std::span<const Eigen::Vector3d> as) const {
    if (rows == 0 || ts.empty()) return false;
    bool plain = true;
    double before = last_t;
    for (std::size_t i = 0; i < ts.size(); ++i) {
      // (|x| < limit is false for NaN; the limit is finite.)
      const double dt = ts[i] - before;
      plain &= static_cast<int>(dt > 0.0) & static_cast<int>(dt <= options.window_s) &
               static_cast<int>(std::abs(as[i][0]) < range_limit) &
               static_cast<int>(std::abs(as[i][1]) < range_limit) &
               static_cast<int>(std::abs(as[i][2]) < range_limit);
      before = ts[i];
    }
    return plain;
  }

  // Takes rows that are Plain, with the reading step among them.
  void TakeRows(std::span<const double> ts, std::span<const Eigen::Vector3d> as) {
    Eigen::Vector3d prev = last_a;
    double smallest = step;
    for (const Eigen::Vector3d& ai : as) {
      for (int k = 0; k < 3; ++k) {
        const double d = std::abs(ai[k] - prev[k]);
        smallest = d > 0.0 && d < smallest ? d : smallest;
      }
      prev = ai;
    }
    step = smallest;
    t.insert(t.end(), ts.begin(), ts.end());
    a.insert(a.end(), as.begin(), as.end());
    last_t = ts.back();
    last_a = as.back();
    rows += ts.size();
  }

  // Sizes the window from the rows buffered so far (all rows until then).
  void SizeWindow() {
    // The first rows only, however many the first pieces brought.
    const std::vector<double> first(
        t.begin(),
        t.begin() + static_cast<std::ptrdiff_t>(std::min(t.size(), period_rows)));
    period_s = first.size() > 1 ? internal::TypicalPeriod(first) : 0.0;
    half = internal::HalfWindowFor(options.window_s, period_s, kSource);
    next_centre = half;
    if (!a.empty()) ref = a.front();
  }

  // One window's statistic, centred on buffered row c.
  void Judge(std::size_t c, double v) {
    if (windows == 0 || v > largest) {
      largest = v;
      largest_at_s = t[c];
    }
    kept.Add(v);
    ++windows;
    if (judged != nullptr) judged->push_back({base + c, t[c], a[c], v});
  }

  // Judges every window now complete, then drops the rows no window needs
  // (the sums slide out the row before the next window).
  void JudgeWindows() {
    if (half == 0) return;
    const std::size_t n = a.size();
    const std::size_t first = next_centre - base;
    if (n < first + half + 1) return;
    internal::ForEachWindow(std::span<const Eigen::Vector3d>(a),
                            half,
                            first,
                            ref,
                            &sums,
                            [this](std::size_t c, double v) { Judge(c, v); });
    next_centre = base + n - half;
    const std::size_t keep_from = next_centre - half - 1;
    if (keep_from - base >= kSliceRows) {
      const auto drop = static_cast<std::ptrdiff_t>(keep_from - base);
      t.erase(t.begin(), t.begin() + drop);
      a.erase(a.begin(), a.begin() + drop);
      base = keep_from;
    }
  }

  StillVerdict VerdictOfSized() const;
  void Init(const DetectOptions& o, AccelUnits units, std::size_t period);
  void Add(std::span<const double> time_s, std::span<const Eigen::Vector3d> accel);
  StillVerdict Verdict() const;
};

StillVerdict MonitorCore::VerdictOfSized() const {
  StillVerdict v;
  v.window_samples = 2 * half + 1;
  v.sample_period_s = period_s;
  v.windows = windows;
  v.gap_at_s = event_at_s;
  if (windows > 0) {
    const double step_floor = std::isfinite(step) ? 0.5 * step : 0.0;
    v.quiet_level = std::max(kept.Quantile(options.quiet_quantile), step_floor);
    v.threshold = options.threshold_factor * v.quiet_level;
    const double cap = options.max_still_g * one_g;
    if (cap > 0.0 && cap < v.threshold) {
      v.threshold = std::max(cap, options.threshold_factor * step_floor);
    }
    v.largest_statistic = largest;
    v.largest_at_s = largest_at_s;
  }
  if (event != NotStillReason::kNone) {
    v.reason = event;
  } else if (windows == 0) {
    v.reason = NotStillReason::kTooShort;
  } else if (largest > v.threshold) {
    v.reason = NotStillReason::kMoved;
  } else {
    v.reason = NotStillReason::kNone;
  }
  v.still = v.reason == NotStillReason::kNone;
  return v;
}

void MonitorCore::Init(const DetectOptions& o, AccelUnits units, std::size_t period) {
  if (const std::string bad = o.Validate(); !bad.empty()) {
    throw Error(ErrorKind::kOption, "static detection options: " + bad);
  }
  options = o;
  period_rows = std::max<std::size_t>(period, 2);
  const auto mps2_per_unit = FixedMps2PerUnit(units);
  counts = !mps2_per_unit.has_value();
  if (counts) return;
  one_g = kStandardGravityMps2 / *mps2_per_unit;
  range_limit = o.range_mps2 > 0.0 ? 0.99 * o.range_mps2 / kStandardGravityMps2 * one_g
                                   : 1.5 * one_g;
}

}  // namespace internal

struct StillnessMonitor::State : internal::MonitorCore {};
struct StillWindows::State : internal::MonitorCore {};

StillnessMonitor::StillnessMonitor(const DetectOptions& options, AccelUnits units)
    : state_(std::make_unique<State>()) {
  state_->Init(options, units, kPeriodRows);
}

StillnessMonitor::~StillnessMonitor() = default;
StillnessMonitor::StillnessMonitor(StillnessMonitor&&) noexcept = default;
StillnessMonitor& StillnessMonitor::operator=(StillnessMonitor&&) noexcept = default;

namespace internal {

void MonitorCore::Add(std::span<const double> time_s,
                      std::span<const Eigen::Vector3d> accel) {
  if (time_s.size() != accel.size()) {
    throw Error(ErrorKind::kInput,
                fmt::format("{}: {} timestamps but {} accelerometer readings",
                            kSource,
                            time_s.size(),
                            accel.size()));
  }
  if (counts) return;
  for (std::size_t b = 0; b < time_s.size() && !stopped; b += kSliceRows) {
    const std::size_t e = std::min(time_s.size(), b + kSliceRows);
    const auto ts = time_s.subspan(b, e - b);
    const auto as = accel.subspan(b, e - b);
    if (Plain(ts, as)) {
      TakeRows(ts, as);
    } else {
      for (std::size_t i = 0; i < ts.size(); ++i) {
        if (!TakeRow(ts[i], as[i])) break;
      }
    }
    if (half == 0 && rows >= period_rows) SizeWindow();
    JudgeWindows();
  }
}

StillVerdict MonitorCore::Verdict() const {
  if (counts) return {};
  if (half > 0) return VerdictOfSized();
  // Fewer rows than the period is taken from: the window from all of them,
  // on a copy (a few thousand rows at most) that reports no window.
  MonitorCore sized = *this;
  sized.judged = nullptr;
  sized.SizeWindow();
  sized.JudgeWindows();
  return sized.VerdictOfSized();
}

}  // namespace internal

void StillnessMonitor::Add(std::span<const double> time_s,
                           std::span<const Eigen::Vector3d> accel) {
  state_->Add(time_s, accel);
}

StillVerdict StillnessMonitor::Verdict() const { return state_->Verdict(); }

StillWindows::StillWindows(const DetectOptions& options,
                           AccelUnits units,
                           std::size_t period_rows)
    : state_(std::make_unique<State>()) {
  state_->Init(options, units, period_rows);
}

StillWindows::~StillWindows() = default;
StillWindows::StillWindows(StillWindows&&) noexcept = default;
StillWindows& StillWindows::operator=(StillWindows&&) noexcept = default;

void StillWindows::Add(std::span<const double> time_s,
                       std::span<const Eigen::Vector3d> accel,
                       std::vector<StillWindow>* judged) {
  state_->judged = judged;
  try {
    state_->Add(time_s, accel);
  } catch (...) {
    state_->judged = nullptr;
    throw;
  }
  state_->judged = nullptr;
}

StillVerdict StillWindows::Verdict() const { return state_->Verdict(); }

}  // namespace mpcal
