// The steps of static detection that carry its rules: what is a still run,
// how much settling is trimmed, when two positions are one across a bump,
// and why a recording gave no position.
#include "detect_steps.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <span>

#include <fmt/format.h>

namespace mpcal::internal {
namespace {

double AngleDeg(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  const double c = u.normalized().dot(v.normalized());
  return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

std::size_t LowerIndex(std::span<const double> t,
                       std::size_t b,
                       std::size_t e,
                       double value) {
  const auto it = std::lower_bound(t.begin() + static_cast<std::ptrdiff_t>(b),
                                   t.begin() + static_cast<std::ptrdiff_t>(e),
                                   value);
  return static_cast<std::size_t>(it - t.begin());
}

std::size_t UpperIndex(std::span<const double> t,
                       std::size_t b,
                       std::size_t e,
                       double value) {
  const auto it = std::upper_bound(t.begin() + static_cast<std::ptrdiff_t>(b),
                                   t.begin() + static_cast<std::ptrdiff_t>(e),
                                   value);
  return static_cast<std::size_t>(it - t.begin());
}

// The time between two pieces that had samples: a stretch with none (the
// logger dropped data; a gap longer than a window ends a run) is not motion.
double GapWithSamples(std::span<const double> t,
                      const Piece& before,
                      const Piece& after,
                      double window_s) {
  double missing_s = 0.0;
  for (std::size_t i = before.end; i <= after.begin; ++i) {
    if (t[i] - t[i - 1] > window_s) missing_s += t[i] - t[i - 1];
  }
  return t[after.begin] - t[before.end - 1] - missing_s;
}

}  // namespace

StillRuns FindStillRuns(std::span<const double> t,
                        const std::vector<double>& stat,
                        std::size_t first,
                        std::size_t last,
                        double threshold,
                        double window_s) {
  StillRuns out;
  std::size_t run_begin = 0;
  bool in_run = false;
  for (std::size_t c = first; c <= last + 1; ++c) {
    const bool still = c <= last && stat[c] <= threshold;
    const bool gap = in_run && c <= last && t[c] - t[c - 1] > window_s;
    if (in_run && (!still || gap)) {
      out.runs.emplace_back(run_begin, c);
      in_run = false;
    }
    if (still) {
      ++out.still_count;
      if (!in_run) {
        run_begin = c;
        in_run = true;
      }
    }
  }
  return out;
}

std::vector<Piece> TrimSettling(std::span<const double> t,
                                std::span<const Eigen::Vector3d> a,
                                const StillRuns& runs,
                                double settle_s,
                                double* longest_still_s) {
  std::vector<Piece> pieces;
  for (const auto& [rb, re] : runs.runs) {
    *longest_still_s = std::max(*longest_still_s, t[re - 1] - t[rb]);
    const std::size_t b = LowerIndex(t, rb, re, t[rb] + settle_s);
    const std::size_t e = UpperIndex(t, rb, re, t[re - 1] - settle_s);
    if (e <= b) continue;  // a flicker below the threshold inside a turn
    pieces.push_back({b, e, MeanOf(a, b, e)});
  }
  return pieces;
}

std::vector<std::vector<Piece>> MergeAcrossBumps(std::span<const double> t,
                                                 const std::vector<Piece>& pieces,
                                                 const Eigen::Vector3d& centre,
                                                 const DetectOptions& options,
                                                 int* merged) {
  std::vector<std::vector<Piece>> groups;
  for (const Piece& p : pieces) {
    if (!groups.empty()) {
      const Piece& prev = groups.back().back();
      // Neither the trimmed settling on both sides nor the window's smear (a
      // bump keeps the statistic high for a window longer than it lasts) is
      // part of the bump.
      const double bump_s = GapWithSamples(t, prev, p, options.window_s) -
                            2.0 * options.settle_s - options.window_s;
      if (bump_s < options.merge_gap_s &&
          AngleDeg(prev.mean - centre, p.mean - centre) < options.merge_angle_deg) {
        groups.back().push_back(p);
        ++*merged;
        continue;
      }
    }
    groups.push_back({p});
  }
  return groups;
}

StaticInterval IntervalOf(const std::vector<Piece>& group,
                          std::span<const double> t,
                          std::span<const Eigen::Vector3d> a) {
  StaticInterval iv;
  iv.begin = group.front().begin;
  iv.end = group.back().end;
  iv.start_s = t[iv.begin];
  iv.end_s = t[iv.end - 1];
  std::size_t used = 0;
  if (group.size() == 1) {
    // MeanOf over the same samples from the same reference: the same sums.
    used = group.front().end - group.front().begin;
    iv.mean = group.front().mean;
  } else {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    const Eigen::Vector3d& r = a[iv.begin];
    for (const Piece& p : group) {
      for (std::size_t i = p.begin; i < p.end; ++i) sum += a[i] - r;
      used += p.end - p.begin;
    }
    iv.mean = r + sum / static_cast<double>(used);
  }
  Eigen::Vector3d sq = Eigen::Vector3d::Zero();
  for (const Piece& p : group) {
    for (std::size_t i = p.begin; i < p.end; ++i) sq += (a[i] - iv.mean).cwiseAbs2();
  }
  if (used > 1) iv.std = (sq / static_cast<double>(used - 1)).cwiseSqrt();
  iv.excluded = (iv.end - iv.begin) - used;
  return iv;
}

DetectFinding Diagnose(const DetectResult& result,
                       const DetectOptions& options,
                       double span_s,
                       bool runs_found,
                       const std::string& clip_limits) {
  DetectFinding f;
  f.span_s = span_s;
  f.window_s = options.window_s;
  f.min_static_s = options.min_static_s;
  f.settle_s = options.settle_s;
  f.threshold_factor = options.threshold_factor;
  f.quiet_quantile = options.quiet_quantile;
  f.max_still_g = options.max_still_g;
  f.threshold = result.threshold;
  f.threshold_capped = result.threshold_capped;
  f.quiet_level = result.quiet_level;
  f.quiet_g =
      result.gravity_units > 0.0 ? result.quiet_level / result.gravity_units : 0.0;
  f.longest_still_s = result.longest_still_s;
  f.dropped_short = result.dropped_short;
  f.dropped_clipped = result.dropped_clipped;
  f.clip_limits = clip_limits;
  if (!result.intervals.empty()) return f;
  if (result.dropped_clipped > 0) {
    f.kind = DetectOutcome::kAllClipped;
    f.advice.settings.push_back({Option::kSensorRange, ""});
  } else if (!runs_found) {
    f.kind = DetectOutcome::kNeverStill;
    f.advice.settings.push_back({Option::kDetectMaxStill, ""});
  } else {
    f.kind = DetectOutcome::kTooShort;
    // The longest stretch passes with 90 % of it as the minimum once half
    // the settling is trimmed.
    f.suggested_min_static_s = std::max(
        0.1, std::floor(9.0 * (result.longest_still_s - options.settle_s)) / 10.0);
    f.suggested_settle_s = options.settle_s / 2.0;
    f.advice.settings.push_back(
        {Option::kDetectMinStatic, fmt::format("{:.2g}", f.suggested_min_static_s)});
    f.advice.settings.push_back(
        {Option::kDetectSettle, fmt::format("{:.2g}", f.suggested_settle_s)});
    // A capped threshold is already at the most a still sensor moves.
    if (!result.threshold_capped) {
      f.advice.settings.push_back({Option::kDetectThreshold, ""});
    }
  }
  return f;
}

}  // namespace mpcal::internal
