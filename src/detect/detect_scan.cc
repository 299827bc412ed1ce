// The passes of static detection over every sample: checks, extremes and
// reading step, the sample period, one g in the recording's units, and the
// readings at the sensor's range limit.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "detect_steps.h"
#include "motion_statistic.h"
#include "mpcal/error.h"
#include "mpcal/not_finite.h"
#include "mpcal/units.h"

namespace mpcal::internal {

double TypicalPeriod(std::span<const double> t) {
  const std::size_t n = t.size();
  const std::size_t stride = std::max<std::size_t>(1, (n - 1) / 100000);
  std::vector<double> dt;
  dt.reserve((n - 1) / stride + 1);
  for (std::size_t i = 1; i < n; i += stride) dt.push_back(t[i] - t[i - 1]);
  // The spacings go to the median itself and are found again for the mean,
  // not kept beside its copy: on a short log the two would be the largest
  // arrays alive after the samples.
  const double limit = 1.5 * Quantile(std::move(dt), 0.5);
  double sum = 0.0;
  std::size_t count = 0;
  for (std::size_t i = 1; i < n; i += stride) {
    const double d = t[i] - t[i - 1];
    if (d <= limit) {
      sum += d;
      ++count;
    }
  }
  return sum / static_cast<double>(count);
}

std::size_t HalfWindowFor(double window_s, double period_s, const std::string& src) {
  if (period_s > 0.0 && window_s < 2.0 * period_s) {
    Advice advice;
    advice.settings.push_back(
        {Option::kDetectWindow, fmt::format("{:.3g}", 3.0 * period_s)});
    throw Error(ErrorKind::kOption,
                fmt::format("{}: the detection window of {} s is shorter than two "
                            "samples ({:.4g} s apart)",
                            src,
                            window_s,
                            period_s),
                advice);
  }
  const std::size_t half =
      period_s > 0.0 ? static_cast<std::size_t>(std::lround(window_s / period_s / 2)) : 1;
  return std::max<std::size_t>(half, 1);
}

SampleScan CheckAndScan(const RecordingView& recording, const std::string& src) {
  const auto& t = recording.time_s;
  const auto& a = recording.accel;
  const std::size_t n = t.size();
  // The message for the first bad sample in [b, e).
  auto fail_in = [&](std::size_t b, std::size_t e) {
    for (std::size_t i = b; i < e; ++i) {
      // The first read of the rows: a view of the caller's memory may hold
      // what no log reader gives.
      if (!std::isfinite(t[i])) throw NotFiniteError(src, RowColumn::kTime, i, t[i]);
      for (int k = 0; k < 3; ++k) {
        if (!std::isfinite(a[i][k]))
          throw NotFiniteError(src, RowColumn::kAccel, i, a[i][k]);
      }
      if (i > 0 && !(t[i] > t[i - 1])) {
        throw Error(
            ErrorKind::kTime,
            fmt::format(
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
      // (|x| <= max is false for NaN and infinities.) A bitwise AND of the
      // four tests on purpose: no branch per value, so the loop vectorises.
      const bool finite = static_cast<int>(std::abs(t[i]) <= kMax) &
                          static_cast<int>(std::abs(a[i][0]) <= kMax) &
                          static_cast<int>(std::abs(a[i][1]) <= kMax) &
                          static_cast<int>(std::abs(a[i][2]) <= kMax);
      bad |= !finite;
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

Eigen::Vector3d MeanOf(std::span<const Eigen::Vector3d> a, std::size_t b, std::size_t e) {
  // A copy, not a reference: read for every sample.
  // NOLINTNEXTLINE(performance-unnecessary-copy-initialization)
  const Eigen::Vector3d ref = a[b];
  Eigen::Vector3d s = Eigen::Vector3d::Zero();
  for (std::size_t i = b; i < e; ++i) s += a[i] - ref;
  return ref + s / static_cast<double>(e - b);
}

SphereFit GravityInUnits(const RecordingView& r,
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

namespace {

// The limits of one axis: from the range given, or where the readings stick
// at their extreme far from the centre; infinite when there is none.
struct AxisLimits {
  double hi = std::numeric_limits<double>::infinity();
  double lo = -std::numeric_limits<double>::infinity();
  bool any() const { return std::isfinite(hi) || std::isfinite(lo); }
};

// Whether axis k of the readings sticks at `level`: 3 identical samples.
bool SticksAt(std::span<const Eigen::Vector3d> a, int k, double level) {
  std::size_t run = 0;
  for (const auto& v : a) {
    run = v[k] == level ? run + 1 : 0;
    if (run >= 3) return true;
  }
  return false;
}

AxisLimits LimitsOf(std::span<const Eigen::Vector3d> a,
                    int k,
                    double range_mps2,
                    const SphereFit& sphere,
                    const SampleScan& scan) {
  AxisLimits limits;
  const double c = sphere.centre[k];
  if (range_mps2 > 0.0) {
    // 99 %: a 16-bit ±2 g sensor tops out at 1.99994 g, and a scale
    // estimated for counts is good to a fraction of a percent.
    const double limit = 0.99 * range_mps2 / kStandardGravityMps2 * sphere.radius;
    limits.hi = c + limit;
    limits.lo = c - limit;
    return limits;
  }
  const double far = 1.5 * sphere.radius;
  if (scan.highest[k] - c >= far && SticksAt(a, k, scan.highest[k])) {
    limits.hi = scan.highest[k];
  }
  if (c - scan.lowest[k] >= far && SticksAt(a, k, scan.lowest[k])) {
    limits.lo = scan.lowest[k];
  }
  return limits;
}

// The limits reached on axis k, as a formula: "|x| >= 8.7", "z >= 32767".
std::string LimitFormula(int k, const AxisLimits& limits, double c, bool from_range) {
  constexpr char kAxes[] = "xyz";
  if (from_range) {
    return c == 0.0 ? fmt::format("|{}| >= {:.6g}", kAxes[k], limits.hi)
                    : fmt::format("|{} - {:.6g}| >= {:.6g}", kAxes[k], c, limits.hi - c);
  }
  std::string side;
  if (std::isfinite(limits.hi)) side = fmt::format("{} >= {:.6g}", kAxes[k], limits.hi);
  if (std::isfinite(limits.lo)) {
    side +=
        fmt::format("{}{} <= {:.6g}", side.empty() ? "" : " or ", kAxes[k], limits.lo);
  }
  return side;
}

}  // namespace

Clipping MarkClipped(std::span<const Eigen::Vector3d> a,
                     double range_mps2,
                     const SphereFit& sphere,
                     const SampleScan& scan) {
  const std::size_t n = a.size();
  Clipping out;
  out.clipped.assign(n, 0);
  if (!(sphere.radius > 0.0)) return out;
  std::vector<std::string> formulas;
  for (int k = 0; k < 3; ++k) {
    const AxisLimits limits = LimitsOf(a, k, range_mps2, sphere, scan);
    // (The readings are finite: with no limit on this axis, none is at one.)
    if (!limits.any()) continue;
    std::size_t count = 0;
    for (std::size_t i = 0; i < n; ++i) {
      if (a[i][k] >= limits.hi || a[i][k] <= limits.lo) {
        out.clipped[i] = 1;
        ++count;
      }
    }
    if (count > 0) {
      formulas.push_back(LimitFormula(k, limits, sphere.centre[k], range_mps2 > 0.0));
    }
  }
  out.limits = fmt::format("{}", fmt::join(formulas, ", "));
  out.count =
      static_cast<std::size_t>(std::count(out.clipped.begin(), out.clipped.end(), 1));
  return out;
}

}  // namespace mpcal::internal
