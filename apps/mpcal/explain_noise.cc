// The noise model held against the Allan curve, in the words a command-line
// user reads (the library gives the cluster times outside, their τ ranges
// and where the fit begins).
#include "explain_noise.h"

#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace mpcal::cli {

// The model against the curve, one cell per axis.
std::string ModelCheckCell(const ModelCheck& c) {
  if (c.points == 0) return "not checked";
  return fmt::format(
      "{} {} of {} outside", c.fits ? "fits:" : "MISSES:", c.outside, c.points);
}

// Where the model misses the curve, and where the short-τ end was left out,
// in words (always printed: a term read there would be wrong).
void PrintModelCheck(const SensorNoise& s, bool gyro, double confidence) {
  const char* sensor = gyro ? "gyroscope" : "accelerometer";
  std::vector<std::string> misses, cut;
  // The axes whose misfit reaches the longest cluster time: there the curve
  // rests on a few degrees of freedom and a slow drift bends it, which a
  // longer record tells apart; elsewhere the curve is already well measured.
  std::vector<char> at_long_end, within;
  for (int i = 0; i < 3; ++i) {
    const ModelCheck& c = s.axes[i].check;
    const char axis = static_cast<char>('x' + i);
    if (!c.fits) {
      const double last_tau_s =
          s.axes[i].curve.empty() ? 0.0 : s.axes[i].curve.back().tau_s;
      bool long_end = false;
      for (const TauRange& r : c.disagree) long_end = long_end || r.hi_s >= last_tau_s;
      (long_end ? at_long_end : within).push_back(axis);
      misses.push_back(fmt::format("{} ({} of {} cluster times, at {})",
                                   axis,
                                   c.outside,
                                   c.points,
                                   FormatTauRanges(c.disagree, 3)));
    }
    if (c.excluded > 0)
      cut.push_back(fmt::format("{} from {:.3g} s", axis, c.from_tau_s));
  }
  if (!misses.empty()) {
    fmt::print(
        "{} model misses the curve (outside its {:.0f} % interval) on {}: the curve "
        "shows an effect the IEEE terms lack (a filter, a Gauss-Markov bump, a "
        "sinusoid, a ramp); the terms that dominate there are not measured.\n",
        sensor,
        100.0 * confidence,
        fmt::join(misses, "; "));
    if (!within.empty()) {
      fmt::print(
          "  on {}: a longer record will not change it: those cluster times are already "
          "well measured, the effect is the sensor's; the terms read elsewhere stand.\n",
          fmt::join(within, ", "));
    }
    if (!at_long_end.empty()) {
      fmt::print(
          "  on {}: it reaches the longest cluster times, where few samples and a slow "
          "drift (a temperature change) bend the curve: a record twice as long shows "
          "whether it stays.\n",
          fmt::join(at_long_end, ", "));
    }
  }
  if (!cut.empty()) {
    fmt::print(
        "{} short-τ end rolls off below the −½ slope (a low-pass filter): fitted {}; "
        "the white noise is read where the −½ slope begins.\n",
        sensor,
        fmt::join(cut, ", "));
  }
}

}  // namespace mpcal::cli
