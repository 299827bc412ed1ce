// Axes for the report's figures: linear scales from data to the plot area,
// "nice" tick positions (1, 2, 5 × 10ⁿ) and their labels, and the frame with
// grid, ticks and axis titles that carry the unit.
#pragma once

#include <string>
#include <vector>

#include "report/svg.h"

namespace mpcal::report {

/// A closed interval of data values.
struct Interval {
  double lo = 0.0;
  double hi = 1.0;
};

/// The smallest and largest finite value of `v` (and of `more`), or
/// {0, 1} when there is none. A degenerate interval is widened.
Interval DataRange(const std::vector<double>& v, const std::vector<double>& more = {});
/// Widens `r` by `fraction` of its span on each side.
Interval Pad(Interval r, double fraction);

/// Ticks at a round step (1, 2 or 5 × 10ⁿ) covering `r` with about `target`
/// of them; `r` is extended outwards to the first and last tick.
struct Ticks {
  std::vector<double> values;
  double step = 1.0;
  Interval range;
  /// When not empty, shown instead of the values (log axes: "10⁻³").
  std::vector<std::string> labels;
};

/// Ticks of a log axis drawn on log10 of the data: one per decade of `r`
/// (in decades), labelled 10ⁿ, `r` extended to whole decades.
Ticks DecadeTicks(Interval r);
Ticks NiceTicks(Interval r, int target);

/// Tick label with as many decimals as the step needs (no "0.30000001").
std::string FormatTick(double v, double step);

/// Maps data to SVG user units, linearly; y grows down in SVG.
struct LinearScale {
  double d0, d1;  ///< data interval
  double r0, r1;  ///< its image
  double operator()(double v) const { return r0 + (v - d0) / (d1 - d0) * (r1 - r0); }
};

/// The plot area inside a figure, in SVG user units.
struct PlotArea {
  double left, top, width, height;
  double right() const { return left + width; }
  double bottom() const { return top + height; }
};

/// Room around a plot's area (user units): tick labels and the rotated y
/// title on the left, the x title below, then a gap before the legend.
struct PlotMargins {
  double left = 74.0;
  double right = 18.0;
  double top = 14.0;
  double bottom = 46.0;
  double legend_gap = 8.0;
};

/// Axis titles with their units, e.g. "time (s)".
struct AxisLabels {
  std::string x;
  std::string y;
};

/// Draws grid lines, the frame, tick labels and the axis titles.
void DrawAxes(Svg& svg,
              const PlotArea& area,
              const Ticks& x_ticks,
              const Ticks& y_ticks,
              const LinearScale& x,
              const LinearScale& y,
              const AxisLabels& labels);

}  // namespace mpcal::report
