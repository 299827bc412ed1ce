#include "report/dot_plot.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>

namespace mpcal::report {

namespace {

// Wider on the left: the rows are labelled with parameter names.
constexpr PlotMargins kDotMargins{.left = 150.0, .top = 10.0};

// The x range of every value and band (and what it must include), padded,
// clipped to ±clip_abs.
Ticks XTicks(const DotPlotSpec& spec) {
  std::vector<double> xs;
  for (const DotRow& r : spec.rows) {
    xs.insert(xs.end(), r.values.begin(), r.values.end());
    if (r.band) {
      xs.push_back(r.band->lo);
      xs.push_back(r.band->hi);
    }
  }
  if (spec.x_include) {
    xs.push_back(spec.x_include->lo);
    xs.push_back(spec.x_include->hi);
  }
  Interval xr = Pad(DataRange(xs), 0.04);
  if (spec.clip_abs) {
    xr.lo = std::max(xr.lo, -*spec.clip_abs);
    xr.hi = std::min(xr.hi, *spec.clip_abs);
  }
  return NiceTicks(xr, 8);
}

// Stripes and bands, under the grid and the points.
void DrawStripesAndBands(Svg& svg,
                         const DotPlotSpec& spec,
                         const PlotArea& area,
                         const LinearScale& x,
                         const LinearScale& y) {
  for (std::size_t i = 0; i < spec.rows.size(); ++i) {
    const DotRow& r = spec.rows[i];
    const double cy = y(static_cast<double>(i) + 0.5);
    if (i % 2 == 1) {
      svg.Rect(
          area.left, y(static_cast<double>(i)), area.width, spec.row_height, "stripe");
    }
    if (r.band) {
      const double x0 = x(r.band->lo);
      svg.Rect(x0,
               cy - spec.row_height * 0.32,
               x(r.band->hi) - x0,
               spec.row_height * 0.64,
               "band");
    }
  }
}

// One row's dots at height cy; values beyond the x range sit at the edge and
// are written once per side.
void DrawRow(Svg& svg,
             const DotRow& r,
             double cy,
             const PlotArea& area,
             const Ticks& xt,
             const LinearScale& x) {
  svg.Text(area.left - 8, cy + 4, r.label, "tick-label", "end");
  svg.OpenGroup("dots", r.label);
  std::vector<std::string> clipped_left;
  std::vector<std::string> clipped_right;
  for (std::size_t g = 0; g < r.values.size(); ++g) {
    if (!std::isfinite(r.values[g])) continue;
    // Spread the groups vertically a little so that equal values stay visible.
    const double dy =
        (static_cast<double>(g) - (static_cast<double>(r.values.size()) - 1) / 2) * 4.0;
    const SeriesStyle style = StandardStyle(static_cast<int>(g));
    const double v = r.values[g];
    if (v < xt.range.lo || v > xt.range.hi) {
      const bool right = v > xt.range.hi;
      svg.Marker(
          style.marker, right ? area.right() - 6 : area.left + 6, cy + dy, 8, style);
      (right ? clipped_right : clipped_left).push_back(fmt::format("{:.0f}", v));
      continue;
    }
    svg.Marker(style.marker, x(v), cy + dy, 8, style);
  }
  if (!clipped_left.empty()) {
    svg.Text(area.left + 14,
             cy + 4,
             fmt::format("{} \u2190", fmt::join(clipped_left, ", ")),
             "point-label",
             "start");
  }
  if (!clipped_right.empty()) {
    svg.Text(area.right() - 14,
             cy + 4,
             fmt::format("\u2192 {}", fmt::join(clipped_right, ", ")),
             "point-label",
             "end");
  }
  svg.CloseGroup();
}

}  // namespace

std::string DotPlot(const DotPlotSpec& spec) {
  std::vector<LegendEntry> legend;
  for (std::size_t g = 0; g < spec.groups.size(); ++g) {
    legend.push_back(
        {spec.groups[g], StandardStyle(static_cast<int>(g)), false, "", false});
  }
  if (!spec.band_legend.empty())
    legend.push_back({spec.band_legend, {}, true, "band", false});
  const double plot_width = spec.width - kDotMargins.left - kDotMargins.right;
  const double legend_height = LegendHeight(legend, plot_width);
  const double plot_height =
      spec.row_height * static_cast<double>(std::max<std::size_t>(spec.rows.size(), 1));
  const double height = kDotMargins.top + plot_height + kDotMargins.bottom;
  const PlotArea area{kDotMargins.left, kDotMargins.top, plot_width, plot_height};
  Svg svg(spec.width,
          height + (legend_height > 0 ? legend_height + kDotMargins.legend_gap : 0),
          spec.aria_label);
  const Ticks xt = XTicks(spec);
  const LinearScale x{xt.range.lo, xt.range.hi, area.left, area.right()};
  const LinearScale y{
      0.0, static_cast<double>(spec.rows.size()), area.top, area.bottom()};
  DrawStripesAndBands(svg, spec, area, x, y);
  Ticks yt;  // rows are labelled by name, not by numeric ticks
  DrawAxes(svg, area, xt, yt, x, y, {spec.x_label, ""});
  for (std::size_t i = 0; i < spec.rows.size(); ++i) {
    DrawRow(svg, spec.rows[i], y(static_cast<double>(i) + 0.5), area, xt, x);
  }
  if (legend_height > 0)
    DrawLegend(svg, legend, area.left, height + kDotMargins.legend_gap, plot_width);
  return svg.Finish();
}

}  // namespace mpcal::report
