// Detection's findings as plain sentences for a library user: the facts with
// their figures, then what to do, naming no option (the command line words
// the advice as its flags, apps/mpcal/explain_detect.cc).
#include <string>

#include <fmt/format.h>

#include "mpcal/detect.h"

namespace mpcal {

std::string DescribeFacts(const DetectFinding& f) {
  switch (f.kind) {
    case DetectOutcome::kFound:
      return "";
    case DetectOutcome::kAllClipped:
      return fmt::format(
          "no usable static position in {:.1f} s: {} found, {} too short, and {} "
          "dropped because they contain readings at the sensor's range limit ({})",
          f.span_s,
          f.dropped_clipped + f.dropped_short,
          f.dropped_short,
          f.dropped_clipped,
          f.clip_limits);
    case DetectOutcome::kNeverStill:
      return fmt::format(
          "no static position found in {:.1f} s: no window of {} s was still "
          "(threshold {:.4g}{}); even the quietest {:.0f}% of the recording moves at "
          "{:.4g} ({:.3g} g): the sensor never stops moving",
          f.span_s,
          f.window_s,
          f.threshold,
          f.threshold_capped ? fmt::format(" = the cap of {} g", f.max_still_g)
                             : fmt::format(" = {} x the quiet level", f.threshold_factor),
          100.0 * f.quiet_quantile,
          f.quiet_level,
          f.quiet_g);
    case DetectOutcome::kTooShort:
      return fmt::format(
          "no static position found in {:.1f} s: the longest still stretch lasts "
          "{:.2f} s, shorter than the minimum {} s after trimming {} s of settling at "
          "each end (threshold {:.4g} = {} x the quiet level {:.4g}{}; {} still "
          "stretches dropped as too short)",
          f.span_s,
          f.longest_still_s,
          f.min_static_s,
          f.settle_s,
          f.threshold,
          f.threshold_factor,
          f.quiet_level,
          f.threshold_capped ? fmt::format(", capped at {} g", f.max_still_g) : "",
          f.dropped_short);
  }
  return "";
}

std::string Describe(const DetectFinding& f) {
  switch (f.kind) {
    case DetectOutcome::kFound:
      return "";
    case DetectOutcome::kAllClipped:
      return DescribeFacts(f) +
             "; keep the sensor within its range, or give its range if that is not "
             "the limit";
    case DetectOutcome::kNeverStill:
      return DescribeFacts(f) +
             ". Hold it still for a few seconds per position; if it is this noisy at "
             "rest, raise the cap of the threshold";
    case DetectOutcome::kTooShort:
      return DescribeFacts(f) +
             fmt::format(
                 ": hold each position longer, or lower the minimum to {:.2g} s and the "
                 "settling to {:.2g} s{}",
                 f.suggested_min_static_s,
                 f.suggested_settle_s,
                 f.threshold_capped ? "" : ", or raise the threshold factor");
  }
  return "";
}

std::string DescribeFacts(const DetectNote& note) {
  switch (note.kind) {
    case DetectNoteKind::kClippedPosition:
      return fmt::format(
          "position {:.1f}-{:.1f} s dropped: {} of its samples are at the sensor's "
          "range limit ({}), which would bias its mean",
          note.start_s,
          note.end_s,
          note.clipped_samples,
          note.clip_limits);
    case DetectNoteKind::kNotStill:
      return fmt::format(
          "even the quietest {:.0f}% of the recording moves at {:.3g} g, more than a "
          "MEMS accelerometer held still shows (under {} g): if the sensor was not "
          "still, the positions found are not static and a calibration from them is "
          "biased",
          100.0 * note.quiet_quantile,
          note.quiet_g,
          note.plausible_quiet_g);
  }
  return "";
}

std::string Describe(const DetectNote& note) {
  if (note.kind == DetectNoteKind::kClippedPosition) {
    return DescribeFacts(note) + "; if that is not the limit, give the sensor's range";
  }
  return DescribeFacts(note);
}

}  // namespace mpcal
