#include "report/bar_chart.h"

#include <algorithm>
#include <cmath>

namespace mpcal::report {

namespace {

constexpr PlotMargins kBarMargins;
// Category labels closer than this (user units) are thinned out.
constexpr double kMinLabelSpacing = 22.0;

}  // namespace

std::string BarChart(const BarChartSpec& spec) {
  std::vector<LegendEntry> legend;
  for (const BarSeries& b : spec.bars) {
    if (!b.name.empty()) legend.push_back({b.name, {}, true, b.css_class, false});
  }
  for (const BarMarkers& m : spec.markers) {
    legend.push_back({m.name, m.style, false, "", false});
  }
  legend.insert(legend.end(), spec.extra_legend.begin(), spec.extra_legend.end());
  const double plot_width = spec.width - kBarMargins.left - kBarMargins.right;
  const double legend_height = LegendHeight(legend, plot_width);
  const PlotArea area{kBarMargins.left,
                      kBarMargins.top,
                      plot_width,
                      spec.height - kBarMargins.top - kBarMargins.bottom};
  Svg svg(spec.width,
          spec.height + (legend_height > 0 ? legend_height + kBarMargins.legend_gap : 0),
          spec.aria_label);

  std::vector<double> values{0.0};
  for (const BarSeries& b : spec.bars) {
    values.insert(values.end(), b.values.begin(), b.values.end());
  }
  for (const BarMarkers& m : spec.markers) {
    for (const auto& v : m.values) {
      if (v) values.push_back(*v);
    }
  }
  const Ticks yt = NiceTicks(Pad(DataRange(values), 0.04), 5);
  const LinearScale y{yt.range.lo, yt.range.hi, area.bottom(), area.top};
  const std::size_t n = std::max<std::size_t>(spec.categories.size(), 1);
  const double slot = area.width / static_cast<double>(n);
  const LinearScale x{0.0, static_cast<double>(n), area.left, area.right()};

  // Category labels play the part of x ticks: every k-th when crowded.
  Ticks xt;
  xt.step = 1.0;
  xt.range = {0.0, static_cast<double>(n)};
  const std::size_t every = std::max<std::size_t>(
      1, static_cast<std::size_t>(std::ceil(kMinLabelSpacing / slot)));
  DrawAxes(svg, area, xt, yt, x, y, spec.axes);
  for (std::size_t i = 0; i < spec.categories.size(); i += every) {
    const double cx = x(static_cast<double>(i) + 0.5);
    svg.Line(cx, area.bottom(), cx, area.bottom() + 4, "tick");
    svg.Text(cx, area.bottom() + 17, spec.categories[i], "tick-label", "middle");
  }
  svg.Line(area.left, y(0.0), area.right(), y(0.0), "zero");

  const double group = slot * 0.8;
  const double bar =
      group / static_cast<double>(std::max<std::size_t>(spec.bars.size(), 1));
  for (std::size_t s = 0; s < spec.bars.size(); ++s) {
    const BarSeries& b = spec.bars[s];
    svg.OpenGroup("bars", b.name);
    for (std::size_t i = 0; i < b.values.size() && i < spec.categories.size(); ++i) {
      const double v = b.values[i];
      if (!std::isfinite(v)) continue;
      const double left =
          x(static_cast<double>(i)) + slot * 0.1 + bar * static_cast<double>(s);
      const double top = std::min(y(v), y(0.0));
      const double h = std::abs(y(v) - y(0.0));
      const std::string& cls =
          i < b.classes.size() && !b.classes[i].empty() ? b.classes[i] : b.css_class;
      svg.Rect(left, top, bar * 0.92, std::max(h, 0.5), cls);
    }
    svg.CloseGroup();
  }
  for (const BarMarkers& m : spec.markers) {
    svg.OpenGroup("markers", m.name);
    for (std::size_t i = 0; i < m.values.size() && i < spec.categories.size(); ++i) {
      if (!m.values[i] || !std::isfinite(*m.values[i])) continue;
      svg.Marker(
          m.style.marker, x(static_cast<double>(i) + 0.5), y(*m.values[i]), 8, m.style);
    }
    svg.CloseGroup();
  }
  if (legend_height > 0) {
    DrawLegend(svg, legend, area.left, spec.height + kBarMargins.legend_gap, plot_width);
  }
  return svg.Finish();
}

}  // namespace mpcal::report
