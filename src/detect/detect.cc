#include "mpcal/detect.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <utility>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "mpcal/coverage.h"
#include "mpcal/error.h"

namespace mpcal {
namespace {

// The motion statistic of a MEMS accelerometer held still, in g: its white
// noise over the three axes (a few mg for consumer parts at 100 Hz, ~0.03 g
// for the noisiest at kHz rates) plus a hand's tremor. A recording whose
// quietest stretches move more than this has no still positions, only
// slower motion; detection says so when a raised --max-still lets it through.
constexpr double kPlausibleQuietG = 0.03;

// The value below which a fraction q of `values` lies (nearest rank).
double Quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  const auto k =
      static_cast<std::size_t>(std::clamp(q * static_cast<double>(values.size() - 1),
                                          0.0,
                                          static_cast<double>(values.size() - 1)));
  std::nth_element(
      values.begin(), values.begin() + static_cast<std::ptrdiff_t>(k), values.end());
  return values[k];
}

// Quantile (as Quantile: nearest rank, exactly) of `count` values that
// `for_each_value(f)` visits again, calling f(value) for each, from a
// strided sample of them (every `stride`th; all when `stride` is 1): the
// sample brackets the rank, and a visit keeps only the values inside the
// bracket, so that millions of values are neither copied nor selected among.
// Visits again, keeping all, when the bracket misses (or a value is NaN).
template <typename ForEachValue>
double QuantileOf(std::vector<double> sample,
                  std::size_t stride,
                  std::size_t count,
                  double q,
                  ForEachValue&& for_each_value) {
  auto keep_all = [&] {
    std::vector<double> all;
    all.reserve(count);
    for_each_value([&](double v) { all.push_back(v); });
    return Quantile(std::move(all), q);
  };
  if (stride <= 1) return Quantile(std::move(sample), q);
  if (sample.empty() || count == 0) return keep_all();
  const auto rank = static_cast<std::size_t>(std::clamp(
      q * static_cast<double>(count - 1), 0.0, static_cast<double>(count - 1)));
  // The sample's rank of q, +- 5 standard deviations of a sampled rank.
  const double m = static_cast<double>(sample.size());
  const double centre = q * (m - 1.0);
  const double margin = 5.0 * std::sqrt(m * std::clamp(q * (1.0 - q), 1e-6, 0.25)) + 16.0;
  auto sample_at = [&](double r) {
    const auto k = static_cast<std::ptrdiff_t>(r);
    std::nth_element(sample.begin(), sample.begin() + k, sample.end());
    return sample[static_cast<std::size_t>(k)];
  };
  const double lo = centre - margin < 0.0 ? -std::numeric_limits<double>::infinity()
                                          : sample_at(centre - margin);
  const double hi = centre + margin > m - 1.0 ? std::numeric_limits<double>::infinity()
                                              : sample_at(centre + margin);
  std::size_t below = 0;
  bool nan = false;
  std::vector<double> inside;
  inside.reserve(4 * static_cast<std::size_t>(margin) * stride);
  for_each_value([&](double v) {
    if (v < lo) {
      ++below;
    } else if (v <= hi) {
      inside.push_back(v);
    } else {
      nan |= std::isnan(v);
    }
  });
  if (nan || rank < below || rank >= below + inside.size()) return keep_all();
  const auto k = static_cast<std::ptrdiff_t>(rank - below);
  std::nth_element(inside.begin(), inside.begin() + k, inside.end());
  return inside[static_cast<std::size_t>(k)];
}

// The motion statistic of the window of 2 half + 1 samples centred on each
// sample c in [half, n - 1 - half], in order: visit(c, statistic). By
// sliding sums over readings centred on the first one (counts near 32768
// would otherwise lose their noise to cancellation). The sums are redone
// from scratch every `resync` steps so that rounding cannot build up over
// millions of samples.
template <typename Visit>
void ForEachWindow(const std::vector<Eigen::Vector3d>& a,
                   std::size_t half,
                   Visit&& visit) {
  const std::size_t n = a.size();
  const std::size_t w = 2 * half + 1;
  const Eigen::Vector3d ref = a[0];
  const std::size_t first = half;
  const std::size_t last = n - 1 - half;  // inclusive
  const std::size_t resync = std::max<std::size_t>(4096, 8 * w);
  Eigen::Vector3d s1 = Eigen::Vector3d::Zero();
  Eigen::Vector3d s2 = Eigen::Vector3d::Zero();
  // Multiplications: six divisions per sample were a third of detection.
  const double inv_w = 1.0 / static_cast<double>(w);
  const double inv_w1 = 1.0 / static_cast<double>(w - 1);
  std::size_t until_resync = 0;  // (c - first) % resync, without a division
  for (std::size_t c = first; c <= last; ++c) {
    const std::size_t lo = c - half;
    const std::size_t hi = c + half;  // inclusive
    if (until_resync-- == 0) {
      until_resync = resync - 1;
      s1.setZero();
      s2.setZero();
      for (std::size_t j = lo; j <= hi; ++j) {
        const Eigen::Vector3d d = a[j] - ref;
        s1 += d;
        s2 += d.cwiseAbs2();
      }
    } else {
      const Eigen::Vector3d add = a[hi] - ref;
      const Eigen::Vector3d sub = a[lo - 1] - ref;
      s1 += add - sub;
      s2 += add.cwiseAbs2() - sub.cwiseAbs2();
    }
    const Eigen::Vector3d var = ((s2 - s1.cwiseAbs2() * inv_w) * inv_w1).cwiseMax(0.0);
    visit(c, std::sqrt(var.sum()));
  }
}

// Typical sample period from (at most ~100k) consecutive differences: the
// mean of those no longer than 1.5 x their median, so that a few gaps do not
// move it, while timestamps rounded to the millisecond (a 160 Hz log spaced
// 6, 6, 7, 6 ms) still give the true rate rather than the rounded step.
double TypicalPeriod(const std::vector<double>& t) {
  const std::size_t n = t.size();
  const std::size_t stride = std::max<std::size_t>(1, (n - 1) / 100000);
  std::vector<double> dt;
  dt.reserve((n - 1) / stride + 1);
  for (std::size_t i = 1; i < n; i += stride) dt.push_back(t[i] - t[i - 1]);
  const double limit = 1.5 * Quantile(dt, 0.5);
  double sum = 0.0;
  std::size_t count = 0;
  for (const double d : dt) {
    if (d <= limit) {
      sum += d;
      ++count;
    }
  }
  return sum / static_cast<double>(count);
}

// What DetectStatic needs from every sample, found in one pass over them
// (a recording has millions).
struct SampleScan {
  // The reading step of a quantised log (ADC counts, or values printed with
  // few decimals): the smallest non-zero change between samples (checked at
  // ~200k places spread over the log). 0 when the signal never changes.
  double resolution_step = 0.0;
  // The extremes of each axis.
  Eigen::Vector3d highest = Eigen::Vector3d::Zero();
  Eigen::Vector3d lowest = Eigen::Vector3d::Zero();
};

// Throws unless every sample is finite and time strictly increases, and
// scans the samples on the way.
SampleScan CheckAndScan(const Recording& recording, const std::string& src) {
  const auto& t = recording.time_s;
  const auto& a = recording.accel;
  const std::size_t n = t.size();
  // The message for the first bad sample in [b, e).
  auto fail_in = [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      if (!std::isfinite(t[i]) || !a[i].allFinite()) {
        throw Error(fmt::format("{}: sample {} (t = {} s) is not finite", src, i, t[i]));
      }
      if (i > 0 && !(t[i] > t[i - 1])) {
        throw Error(fmt::format(
            "{}: time does not increase at sample {} ({} s after {} s); the static "
            "detector needs a strictly increasing time column",
            src,
            i,
            t[i],
            t[i - 1]));
      }
    }
  };
  constexpr double kMax = std::numeric_limits<double>::max();
  constexpr std::size_t kBlock = 4096;  // checked without a branch per sample
  // The extremes in locals, not in `scan`: stores the compiler could not
  // keep in registers (a[i] might alias them) doubled this loop's time.
  Eigen::Array3d highest = a[0];
  Eigen::Array3d lowest = a[0];
  double step = std::numeric_limits<double>::infinity();
  const std::size_t stride = std::max<std::size_t>(1, n / 200000);
  std::size_t next_step = stride;
  for (std::size_t b = 0; b < n; b += kBlock) {
    const std::size_t e = std::min(n, b + kBlock);
    bool bad = false;
    for (std::size_t i = b; i < e; ++i) {
      // (|x| <= max is false for NaN and infinities.)
      bad |= !(std::abs(t[i]) <= kMax) | !(std::abs(a[i][0]) <= kMax) |
             !(std::abs(a[i][1]) <= kMax) | !(std::abs(a[i][2]) <= kMax);
    }
    for (std::size_t i = std::max<std::size_t>(b, 1); i < e; ++i)
      bad |= !(t[i] > t[i - 1]);
    if (bad) fail_in(b, e);
    for (std::size_t i = b; i < e; ++i) {
      highest = highest.max(a[i].array());
      lowest = lowest.min(a[i].array());
    }
    for (; next_step < e; next_step += stride) {
      for (int k = 0; k < 3; ++k) {
        const double d = std::abs(a[next_step][k] - a[next_step - 1][k]);
        if (d > 0.0 && d < step) step = d;
      }
    }
  }
  SampleScan scan;
  scan.highest = highest;
  scan.lowest = lowest;
  scan.resolution_step = std::isfinite(step) ? step : 0.0;
  return scan;
}

struct Piece {
  std::size_t begin = 0;  // kept samples [begin, end) after trimming
  std::size_t end = 0;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
};

Eigen::Vector3d MeanOf(const std::vector<Eigen::Vector3d>& a,
                       std::size_t b,
                       std::size_t e) {
  // Centred on the first sample so that counts near 32768 keep their digits.
  const Eigen::Vector3d ref = a[b];
  Eigen::Vector3d s = Eigen::Vector3d::Zero();
  for (std::size_t i = b; i < e; ++i) s += a[i] - ref;
  return ref + s / static_cast<double>(e - b);
}

// One g in the recording's units: fixed for g and m/s²; for counts the radius
// of a sphere through the means of the still windows (at most ~2000 of them,
// consecutive and not overlapping), which a session that turns the sensor
// about spreads over the sphere. Windows in a turn would pull it inwards.
// Also the centre of that sphere (0 for g and m/s²), about which clipping
// limits are measured.
SphereFit GravityInUnits(const Recording& r,
                         const std::vector<double>& stat,
                         std::size_t w,
                         double still_level) {
  if (const auto fixed = FixedMps2PerUnit(r.units)) {
    SphereFit nominal;
    nominal.radius = kStandardGravityMps2 / *fixed;
    return nominal;
  }
  const std::size_t blocks = r.size() / w;
  std::vector<std::size_t> still;
  for (std::size_t b = 0; b < blocks; ++b) {
    if (stat[b * w + w / 2] <= still_level) still.push_back(b);
  }
  if (still.size() < 4) {
    still.resize(blocks);
    for (std::size_t b = 0; b < blocks; ++b) still[b] = b;
  }
  const std::size_t stride = std::max<std::size_t>(1, still.size() / 2000);
  std::vector<Eigen::Vector3d> means;
  for (std::size_t k = 0; k < still.size(); k += stride) {
    means.push_back(MeanOf(r.accel, still[k] * w, (still[k] + 1) * w));
  }
  return FitSphere(means, r.units);
}

// Marks the samples at the sensor's range limit (see
// DetectOptions::range_mps2); `sphere` is one g and the zero in the
// recording's units, `scan` has the readings' extremes. Returns the number
// marked.
std::size_t MarkClipped(const std::vector<Eigen::Vector3d>& a,
                        double range_mps2,
                        const SphereFit& sphere,
                        const SampleScan& scan,
                        std::vector<std::uint8_t>* clipped,
                        std::string* what) {
  const std::size_t n = a.size();
  clipped->assign(n, 0);
  if (!(sphere.radius > 0.0)) return 0;
  constexpr char kAxes[] = "xyz";
  std::vector<std::string> limits;
  for (int k = 0; k < 3; ++k) {
    const double c = sphere.centre[k];
    double hi_limit = std::numeric_limits<double>::infinity();
    double lo_limit = -hi_limit;
    if (range_mps2 > 0.0) {
      // 99 %: a 16-bit ±2 g sensor tops out at 1.99994 g, and a scale
      // estimated for counts is good to a fraction of a percent.
      const double limit = 0.99 * range_mps2 / kStandardGravityMps2 * sphere.radius;
      hi_limit = c + limit;
      lo_limit = c - limit;
    } else {
      const double hi = scan.highest[k];
      const double lo = scan.lowest[k];
      // A level counts when the sensor sticks there: 3 identical samples.
      auto sticks_at = [&](double level) {
        std::size_t run = 0;
        for (const auto& v : a) {
          run = v[k] == level ? run + 1 : 0;
          if (run >= 3) return true;
        }
        return false;
      };
      const double far = 1.5 * sphere.radius;
      if (hi - c >= far && sticks_at(hi)) hi_limit = hi;
      if (c - lo >= far && sticks_at(lo)) lo_limit = lo;
    }
    std::size_t count = 0;
    // (The readings are finite: with no limit on this axis, none is at one.)
    const bool limited = std::isfinite(hi_limit) || std::isfinite(lo_limit);
    for (std::size_t i = 0; limited && i < n; ++i) {
      if (a[i][k] >= hi_limit || a[i][k] <= lo_limit) {
        (*clipped)[i] = 1;
        ++count;
      }
    }
    if (count > 0 && range_mps2 > 0.0) {
      limits.push_back(
          c == 0.0 ? fmt::format("|{}| >= {:.6g}", kAxes[k], hi_limit)
                   : fmt::format("|{} - {:.6g}| >= {:.6g}", kAxes[k], c, hi_limit - c));
    } else if (count > 0) {
      std::string side;
      if (std::isfinite(hi_limit)) side = fmt::format("{} >= {:.6g}", kAxes[k], hi_limit);
      if (std::isfinite(lo_limit)) {
        side +=
            fmt::format("{}{} <= {:.6g}", side.empty() ? "" : " or ", kAxes[k], lo_limit);
      }
      limits.push_back(side);
    }
  }
  *what = fmt::format("{}", fmt::join(limits, ", "));
  return static_cast<std::size_t>(std::count(clipped->begin(), clipped->end(), 1));
}

double AngleDeg(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  const double c = u.normalized().dot(v.normalized());
  return std::acos(std::clamp(c, -1.0, 1.0)) * 180.0 / std::numbers::pi;
}

}  // namespace

std::string DetectOptions::Validate() const {
  if (!(window_s > 0.0) || !std::isfinite(window_s)) return "window_s must be > 0";
  if (!(min_static_s > 0.0) || !std::isfinite(min_static_s))
    return "min_static_s must be > 0";
  if (!(settle_s >= 0.0) || !std::isfinite(settle_s)) return "settle_s must be >= 0";
  if (!(threshold_factor >= 1.0) || !std::isfinite(threshold_factor))
    return "threshold_factor must be >= 1";
  if (!(quiet_quantile > 0.0 && quiet_quantile < 1.0))
    return "quiet_quantile must be in (0, 1)";
  if (!(max_still_g >= 0.0) || !std::isfinite(max_still_g))
    return "max_still_g must be >= 0";
  if (!(merge_gap_s >= 0.0) || !std::isfinite(merge_gap_s))
    return "merge_gap_s must be >= 0";
  if (!(merge_angle_deg >= 0.0 && merge_angle_deg <= 180.0))
    return "merge_angle_deg must be in [0, 180]";
  if (!(range_mps2 >= 0.0) || !std::isfinite(range_mps2))
    return "range_mps2 must be >= 0 (0: found from the data)";
  return "";
}

DetectResult DetectStatic(const Recording& recording, const DetectOptions& options) {
  if (const std::string bad = options.Validate(); !bad.empty()) {
    throw Error("static detection options: " + bad);
  }
  const std::string src = recording.source.empty() ? "recording" : recording.source;
  const std::size_t n = recording.size();
  if (n == 0)
    throw Error(src + ": the recording is empty: no samples to detect positions in");
  if (recording.accel.size() != n) {
    throw Error(fmt::format("{}: {} timestamps but {} accelerometer readings",
                            src,
                            n,
                            recording.accel.size()));
  }
  const auto& t = recording.time_s;
  const auto& a = recording.accel;
  const SampleScan scan = CheckAndScan(recording, src);

  DetectResult result;
  const double period = n > 1 ? TypicalPeriod(t) : 0.0;
  // Odd window so that it is centred on its sample; 3 samples at least so
  // that a second difference fits in it.
  std::size_t half =
      period > 0.0 ? static_cast<std::size_t>(std::lround(options.window_s / period / 2))
                   : 1;
  half = std::max<std::size_t>(half, 1);
  const std::size_t w = 2 * half + 1;
  result.window_samples = w;
  result.sample_period_s = period;
  if (n < w) {
    throw Error(fmt::format(
        "{}: the recording has {} samples ({:.3g} s), shorter than one detection window "
        "of {} s ({} samples): record longer, or lower --window",
        src,
        n,
        n > 1 ? t[n - 1] - t[0] : 0.0,
        options.window_s,
        w));
  }

  // Motion statistic at every window centre (ForEachWindow); infinite
  // where no window fits.
  const std::size_t first = half;
  const std::size_t last = n - 1 - half;  // inclusive
  // Written in place: a push_back per sample kept the statistic out of
  // registers and cost more than initialising the vector first.
  std::vector<double> stat(n, std::numeric_limits<double>::infinity());
  ForEachWindow(a, half, [&stat](std::size_t c, double v) { stat[c] = v; });
  const std::size_t centres = last + 1 - first;
  constexpr std::size_t kSample = 65536;
  const std::size_t stride = centres <= 4 * kSample ? 1 : centres / kSample;
  std::vector<double> sample;
  sample.reserve(centres / stride + 1);
  for (std::size_t c = first; c <= last; c += stride) sample.push_back(stat[c]);
  auto each_centre = [&](auto&& f) {
    for (std::size_t c = first; c <= last; ++c) f(stat[c]);
  };

  // Quiet level: a low quantile over the window centres. A log quantised
  // coarser than its noise has many windows with no change at all; half a
  // reading step keeps the threshold above the flicker of one step.
  const double quiet_raw =
      QuantileOf(std::move(sample), stride, centres, options.quiet_quantile, each_centre);
  const double step_floor = 0.5 * scan.resolution_step;
  result.quiet_level = std::max(quiet_raw, step_floor);
  result.threshold = options.threshold_factor * result.quiet_level;
  const SphereFit sphere = GravityInUnits(recording, stat, w, result.threshold);
  result.gravity_units = sphere.radius;

  // Readings at the range limit: a saturated axis does not move, so its
  // windows stay out of the quiet level, and a position with any is dropped.
  std::vector<std::uint8_t> clipped;
  std::string clip_limits;
  std::vector<std::size_t> clipped_before;  // clipped samples in [0, i)
  result.clipped_samples =
      MarkClipped(a, options.range_mps2, sphere, scan, &clipped, &clip_limits);
  if (result.clipped_samples > 0) {
    clipped_before.assign(n + 1, 0);
    for (std::size_t i = 0; i < n; ++i)
      clipped_before[i + 1] = clipped_before[i] + clipped[i];
    std::vector<double> unclipped;
    for (std::size_t c = first; c <= last; ++c) {
      if (clipped_before[c + half + 1] == clipped_before[c - half])
        unclipped.push_back(stat[c]);
    }
    if (!unclipped.empty()) {
      result.quiet_level =
          std::max(Quantile(std::move(unclipped), options.quiet_quantile), step_floor);
      result.threshold = options.threshold_factor * result.quiet_level;
    }
  }
  const double cap = options.max_still_g * result.gravity_units;
  if (cap > 0.0 && cap < result.threshold) {
    result.threshold = std::max(cap, options.threshold_factor * step_floor);
    result.threshold_capped = true;
  }

  // Runs of still window centres; a time gap longer than a window ends a run
  // (the statistic cannot see what happened in it).
  std::vector<std::pair<std::size_t, std::size_t>> runs;
  std::size_t still_count = 0;
  {
    std::size_t run_begin = 0;
    bool in_run = false;
    for (std::size_t c = first; c <= last + 1; ++c) {
      const bool still = c <= last && stat[c] <= result.threshold;
      const bool gap = in_run && c <= last && t[c] - t[c - 1] > options.window_s;
      if (in_run && (!still || gap)) {
        runs.emplace_back(run_begin, c);
        in_run = false;
      }
      if (still) {
        ++still_count;
        if (!in_run) {
          run_begin = c;
          in_run = true;
        }
      }
    }
  }
  result.still_fraction = static_cast<double>(still_count) / static_cast<double>(n);

  // Trim the settling at both ends of each run.
  std::vector<Piece> pieces;
  for (const auto& [rb, re] : runs) {
    result.longest_still_s = std::max(result.longest_still_s, t[re - 1] - t[rb]);
    const double keep_from = t[rb] + options.settle_s;
    const double keep_to = t[re - 1] - options.settle_s;
    const auto b = static_cast<std::size_t>(
        std::lower_bound(t.begin() + static_cast<std::ptrdiff_t>(rb),
                         t.begin() + static_cast<std::ptrdiff_t>(re),
                         keep_from) -
        t.begin());
    const auto e = static_cast<std::size_t>(
        std::upper_bound(t.begin() + static_cast<std::ptrdiff_t>(rb),
                         t.begin() + static_cast<std::ptrdiff_t>(re),
                         keep_to) -
        t.begin());
    if (e <= b) continue;  // a flicker below the threshold inside a turn
    pieces.push_back({b, e, MeanOf(a, b, e)});
  }

  // Orientation of a piece about the offset of the readings (raw counts sit
  // near 32768): the centre of a sphere fitted to the longer pieces.
  std::vector<Eigen::Vector3d> long_means;
  for (const Piece& p : pieces) {
    if (t[p.end - 1] - t[p.begin] >= 0.5 * options.min_static_s) {
      long_means.push_back(p.mean);
    }
  }
  const Eigen::Vector3d centre = FitSphere(long_means, recording.units).centre;

  // Merge neighbours at the same orientation across a short bump; the bump
  // itself stays out of the mean.
  std::vector<std::vector<Piece>> groups;
  for (const Piece& p : pieces) {
    if (!groups.empty()) {
      const Piece& prev = groups.back().back();
      // A stretch with no samples (the logger dropped data: a gap longer
      // than a window ends a run above) is not motion: at the same
      // orientation on both sides, the position went on through it.
      double missing_s = 0.0;
      for (std::size_t i = prev.end; i <= p.begin; ++i) {
        if (t[i] - t[i - 1] > options.window_s) missing_s += t[i] - t[i - 1];
      }
      const double gap_s = t[p.begin] - t[prev.end - 1] - missing_s;
      // Neither the trimmed settling on both sides nor the window's smear (a
      // bump keeps the statistic high for a window longer than it lasts) is
      // part of the bump.
      const double bump_s = gap_s - 2.0 * options.settle_s - options.window_s;
      if (bump_s < options.merge_gap_s &&
          AngleDeg(prev.mean - centre, p.mean - centre) < options.merge_angle_deg) {
        groups.back().push_back(p);
        ++result.merged;
        continue;
      }
    }
    groups.push_back({p});
  }

  for (const auto& group : groups) {
    StaticInterval iv;
    iv.begin = group.front().begin;
    iv.end = group.back().end;
    iv.start_s = t[iv.begin];
    iv.end_s = t[iv.end - 1];
    if (iv.duration_s() < options.min_static_s) {
      ++result.dropped_short;
      continue;
    }
    if (!clipped_before.empty() && clipped_before[iv.end] > clipped_before[iv.begin]) {
      ++result.dropped_clipped;
      result.warnings.push_back(fmt::format(
          "position {:.1f}-{:.1f} s dropped: {} of its samples are at the sensor's range "
          "limit ({}), which would bias its mean; if that is not the limit, give the "
          "sensor's range with --range",
          iv.start_s,
          iv.end_s,
          clipped_before[iv.end] - clipped_before[iv.begin],
          clip_limits));
      continue;
    }
    std::size_t used = 0;
    if (group.size() == 1) {
      // MeanOf over the same samples from the same reference: the same sums.
      used = group.front().end - group.front().begin;
      iv.mean = group.front().mean;
    } else {
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      const Eigen::Vector3d r = a[iv.begin];
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
    result.intervals.push_back(iv);
  }

  const double quiet_g =
      result.gravity_units > 0.0 ? result.quiet_level / result.gravity_units : 0.0;
  if (!result.intervals.empty() && quiet_g > kPlausibleQuietG) {
    result.warnings.push_back(fmt::format(
        "even the quietest {:.0f}% of the recording moves at {:.3g} g, more than a MEMS "
        "accelerometer held still shows (under {} g): if the sensor was not still, the "
        "positions found are not static and a calibration from them is biased",
        100.0 * options.quiet_quantile,
        quiet_g,
        kPlausibleQuietG));
  }

  if (result.intervals.empty()) {
    const double span_s = t[n - 1] - t[0];
    if (result.dropped_clipped > 0) {
      result.message = fmt::format(
          "no usable static position in {:.1f} s: {} found, {} too short, and {} dropped "
          "because they contain readings at the sensor's range limit ({}); keep the "
          "sensor "
          "within its range, or give the range with --range if that is not the limit",
          span_s,
          result.dropped_clipped + result.dropped_short,
          result.dropped_short,
          result.dropped_clipped,
          clip_limits);
    } else if (runs.empty()) {
      result.message = fmt::format(
          "no static position found in {:.1f} s: no window of {} s was still "
          "(threshold {:.4g}{}); even the quietest {:.0f}% of the recording moves at "
          "{:.4g} ({:.3g} g): the sensor never stops moving. Hold it still for a few "
          "seconds per position; if it is this noisy at rest, raise --max-still",
          span_s,
          options.window_s,
          result.threshold,
          result.threshold_capped
              ? fmt::format(" = the cap of {} g", options.max_still_g)
              : fmt::format(" = {} x the quiet level", options.threshold_factor),
          100.0 * options.quiet_quantile,
          result.quiet_level,
          result.gravity_units > 0.0 ? result.quiet_level / result.gravity_units : 0.0);
    } else {
      result.message = fmt::format(
          "no static position found in {:.1f} s: the longest still stretch lasts "
          "{:.2f} s, shorter than the minimum {} s after trimming {} s of settling at "
          "each end (threshold {:.4g} = {} x the quiet level {:.4g}{}; {} still "
          "stretches dropped as too short): hold each position longer, or try "
          "--min-static {:.2g} --settle {:.2g}{}",
          span_s,
          result.longest_still_s,
          options.min_static_s,
          options.settle_s,
          result.threshold,
          options.threshold_factor,
          result.quiet_level,
          result.threshold_capped ? fmt::format(", capped at {} g", options.max_still_g)
                                  : "",
          result.dropped_short,
          std::max(0.1,
                   std::floor(9.0 * (result.longest_still_s - options.settle_s)) / 10.0),
          options.settle_s / 2.0,
          // A capped threshold is already at the most a still sensor moves.
          result.threshold_capped ? "" : ", or a larger --threshold");
    }
  }
  return result;
}

}  // namespace mpcal
