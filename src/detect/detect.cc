// Static detection: the steps (detect_steps.h) run in order.
#include "mpcal/detect.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <span>
#include <utility>

#include <fmt/format.h>

#include "detect_steps.h"
#include "motion_statistic.h"
#include "mpcal/count.h"
#include "mpcal/error.h"
#include "mpcal/sphere_fit.h"

namespace mpcal {
namespace {

using internal::Clipping;
using internal::Piece;

// The motion statistic of a MEMS accelerometer held still, in g: its white
// noise over the three axes (a few mg for consumer parts at 100 Hz, ~0.03 g
// for the noisiest at kHz rates) plus a hand's tremor. A recording whose
// quietest stretches move more than this has no still positions, only
// slower motion; detection says so when a raised cap lets it through.
constexpr double kPlausibleQuietG = 0.03;

// Throws unless the options are valid and the recording has one reading per
// time stamp and at least one sample. Returns the recording's name.
std::string CheckCall(const RecordingView& recording, const DetectOptions& options) {
  if (const std::string bad = options.Validate(); !bad.empty()) {
    throw Error(ErrorKind::kOption, "static detection options: " + bad);
  }
  std::string src =
      recording.source.empty() ? "recording" : std::string(recording.source);
  const std::size_t n = recording.size();
  if (n == 0) {
    throw Error(ErrorKind::kInput,
                src + ": the recording is empty: no samples to detect positions in");
  }
  if (recording.accel.size() != n) {
    throw Error(ErrorKind::kInput,
                fmt::format("{}: {} timestamps but {} accelerometer readings",
                            src,
                            n,
                            recording.accel.size()));
  }
  return src;
}

// Half the moving window in samples: odd, so that it is centred on its
// sample, and 3 samples at least so that a second difference fits in it.
// Throws when the window asked for is shorter than two samples (it would
// silently be three) or the recording shorter than one window.
std::size_t HalfWindow(const RecordingView& recording,
                       const DetectOptions& options,
                       const std::string& src,
                       DetectResult* result) {
  const auto& t = recording.time_s;
  const std::size_t n = t.size();
  const double period = n > 1 ? internal::TypicalPeriod(t) : 0.0;
  const std::size_t half = internal::HalfWindowFor(options.window_s, period, src);
  const std::size_t w = 2 * half + 1;
  result->window_samples = w;
  result->sample_period_s = period;
  if (n < w) {
    Advice advice;
    advice.settings.push_back({Option::kDetectWindow, ""});
    throw Error(ErrorKind::kSession,
                fmt::format("{}: the recording has {} ({:.3g} s), shorter than "
                            "one detection window of {} s ({}): record longer, or "
                            "shorten the window",
                            src,
                            Count(n, "sample"),
                            n > 1 ? t[n - 1] - t[0] : 0.0,
                            options.window_s,
                            Count(w, "sample")),
                advice);
  }
  return half;
}

// Quiet level: a low quantile over the window centres [first, last]. A log
// quantised coarser than its noise has many windows with no change at all;
// half a reading step (`step_floor`) keeps the threshold above the flicker
// of one step.
double QuietLevel(const std::vector<double>& stat,
                  std::size_t first,
                  std::size_t last,
                  double quantile,
                  double step_floor) {
  const std::size_t centres = last + 1 - first;
  // A strided sample brackets the quantile and QuantileOf selects among the
  // values inside the bracket only (exactly the quantile of every centre); a
  // copy of every centre would be as large as the statistic itself, on a
  // short log the largest array alive beside the samples.
  constexpr std::size_t kSample = 8192;
  const std::size_t stride = std::max<std::size_t>(1, centres / kSample);
  std::vector<double> sample;
  sample.reserve(centres / stride + 1);
  for (std::size_t c = first; c <= last; c += stride) sample.push_back(stat[c]);
  auto each_centre = [&](auto&& f) {
    for (std::size_t c = first; c <= last; ++c) f(stat[c]);
  };
  const double raw =
      internal::QuantileOf(std::move(sample), stride, centres, quantile, each_centre);
  return std::max(raw, step_floor);
}

// Clipped samples in [0, i) for every i, so that any range is counted in
// O(1); empty when none is clipped.
std::vector<std::size_t> ClippedBefore(const Clipping& clipping) {
  std::vector<std::size_t> before;
  if (clipping.count == 0) return before;
  const std::size_t n = clipping.clipped.size();
  before.assign(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) before[i + 1] = before[i] + clipping.clipped[i];
  return before;
}

// The quiet level without the windows that hold a clipped sample: a
// saturated axis does not move, so its windows would pull the level down.
void RequantileUnclipped(const std::vector<double>& stat,
                         std::size_t half,
                         const std::vector<std::size_t>& clipped_before,
                         const DetectOptions& options,
                         double step_floor,
                         DetectResult* result) {
  if (clipped_before.empty()) return;
  const std::size_t last = stat.size() - 1 - half;
  std::vector<double> unclipped;
  for (std::size_t c = half; c <= last; ++c) {
    if (clipped_before[c + half + 1] == clipped_before[c - half])
      unclipped.push_back(stat[c]);
  }
  if (unclipped.empty()) return;
  result->quiet_level = std::max(
      internal::Quantile(std::move(unclipped), options.quiet_quantile), step_floor);
  result->threshold = options.threshold_factor * result->quiet_level;
}

// The offset of the readings (raw counts sit near 32768) that orientations
// are measured about: the centre of a sphere fitted to the longer pieces.
Eigen::Vector3d OrientationCentre(std::span<const double> t,
                                  const std::vector<Piece>& pieces,
                                  const DetectOptions& options,
                                  AccelUnits units) {
  std::vector<Eigen::Vector3d> long_means;
  for (const Piece& p : pieces) {
    if (t[p.end - 1] - t[p.begin] >= 0.5 * options.min_static_s) {
      long_means.push_back(p.mean);
    }
  }
  return FitSphere(long_means, units).centre;
}

// The intervals of the groups that are long enough and hold no clipped
// sample; the others are counted (and a clipped one noted).
void KeepIntervals(const std::vector<std::vector<Piece>>& groups,
                   const RecordingView& recording,
                   const DetectOptions& options,
                   const std::vector<std::size_t>& clipped_before,
                   const std::string& clip_limits,
                   DetectResult* result) {
  const auto& t = recording.time_s;
  for (const auto& group : groups) {
    const std::size_t b = group.front().begin;
    const std::size_t e = group.back().end;
    if (t[e - 1] - t[b] < options.min_static_s) {
      ++result->dropped_short;
      continue;
    }
    if (!clipped_before.empty() && clipped_before[e] > clipped_before[b]) {
      ++result->dropped_clipped;
      DetectNote note;
      note.kind = DetectNoteKind::kClippedPosition;
      note.start_s = t[b];
      note.end_s = t[e - 1];
      note.clipped_samples = clipped_before[e] - clipped_before[b];
      note.clip_limits = clip_limits;
      note.advice.settings.push_back({Option::kSensorRange, ""});
      result->notes.push_back(note);
      continue;
    }
    result->intervals.push_back(internal::IntervalOf(group, t, recording.accel));
  }
}

// A note when even the quietest part of the recording moves more than a
// still MEMS accelerometer does (the cap was raised past it).
void NoteIfNeverQuiet(const DetectOptions& options, DetectResult* result) {
  const double quiet_g =
      result->gravity_units > 0.0 ? result->quiet_level / result->gravity_units : 0.0;
  if (result->intervals.empty() || quiet_g <= kPlausibleQuietG) return;
  DetectNote note;
  note.kind = DetectNoteKind::kNotStill;
  note.quiet_g = quiet_g;
  note.quiet_quantile = options.quiet_quantile;
  note.plausible_quiet_g = kPlausibleQuietG;
  result->notes.push_back(note);
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

DetectResult DetectStatic(const RecordingView& recording, const DetectOptions& options) {
  const std::string src = CheckCall(recording, options);
  const auto& t = recording.time_s;
  const auto& a = recording.accel;
  const std::size_t n = recording.size();
  const internal::SampleScan scan = internal::CheckAndScan(recording, src);

  DetectResult result;
  const std::size_t half = HalfWindow(recording, options, src, &result);
  const std::size_t w = 2 * half + 1;

  // Motion statistic at every window centre; infinite where no window fits.
  // Written in place: a push_back per sample kept the statistic out of
  // registers and cost more than initialising the vector first.
  std::vector<double> stat(n, std::numeric_limits<double>::infinity());
  internal::ForEachWindow(a, half, [&stat](std::size_t c, double v) { stat[c] = v; });

  const double step_floor = 0.5 * scan.resolution_step;
  result.quiet_level =
      QuietLevel(stat, half, n - 1 - half, options.quiet_quantile, step_floor);
  result.threshold = options.threshold_factor * result.quiet_level;
  const SphereFit sphere = internal::GravityInUnits(recording, stat, w, result.threshold);
  result.gravity_units = sphere.radius;

  // Readings at the range limit stay out of the quiet level, and a position
  // with any is dropped.
  const Clipping clipping = internal::MarkClipped(a, options.range_mps2, sphere, scan);
  result.clipped_samples = clipping.count;
  const std::vector<std::size_t> clipped_before = ClippedBefore(clipping);
  RequantileUnclipped(stat, half, clipped_before, options, step_floor, &result);
  const double cap = options.max_still_g * result.gravity_units;
  if (cap > 0.0 && cap < result.threshold) {
    result.threshold = std::max(cap, options.threshold_factor * step_floor);
    result.threshold_capped = true;
  }

  const internal::StillRuns runs = internal::FindStillRuns(
      t, stat, half, n - 1 - half, result.threshold, options.window_s);
  result.still_fraction = static_cast<double>(runs.still_count) / static_cast<double>(n);
  const std::vector<Piece> pieces =
      internal::TrimSettling(t, a, runs, options.settle_s, &result.longest_still_s);
  const Eigen::Vector3d centre = OrientationCentre(t, pieces, options, recording.units);
  const auto groups =
      internal::MergeAcrossBumps(t, pieces, centre, options, &result.merged);
  KeepIntervals(groups, recording, options, clipped_before, clipping.limits, &result);
  NoteIfNeverQuiet(options, &result);
  result.finding = internal::Diagnose(
      result, options, t[n - 1] - t[0], !runs.runs.empty(), clipping.limits);
  return result;
}

}  // namespace mpcal
