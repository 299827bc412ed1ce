#include "report/line_plot.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>

namespace mpcal::report {

namespace {

constexpr PlotMargins kMargins;

// Ticks at `step` strictly inside a fixed range (equal-scale plots cannot
// extend their range to the next round number).
Ticks TicksInside(Interval r, double step) {
  Ticks t;
  t.step = step;
  t.range = r;
  for (double v = std::ceil(r.lo / step - 1e-9) * step; v <= r.hi + 1e-9 * step;
       v += step) {
    t.values.push_back(std::abs(v) < 1e-9 * step ? 0.0 : v);
  }
  return t;
}

// log10 of every value (non-positive values become NaN and are skipped).
std::vector<double> Log10(const std::vector<double>& v) {
  std::vector<double> out(v.size());
  for (std::size_t i = 0; i < v.size(); ++i) {
    out[i] = v[i] > 0.0 ? std::log10(v[i]) : std::numeric_limits<double>::quiet_NaN();
  }
  return out;
}

// The spec with its data on log10 scales where asked: the plot is then drawn
// linearly and only the ticks know it was logarithmic.
LinePlotSpec ToLogScales(const LinePlotSpec& in) {
  LinePlotSpec s = in;
  const auto lx = [&](const std::vector<double>& v) { return in.log_x ? Log10(v) : v; };
  const auto ly = [&](const std::vector<double>& v) { return in.log_y ? Log10(v) : v; };
  const auto one = [](bool log, double v) { return log ? std::log10(v) : v; };
  for (Series& series : s.series) {
    series.x = lx(series.x);
    series.y = ly(series.y);
  }
  for (FillBetween& f : s.fills) {
    f.x = lx(f.x);
    f.lo = ly(f.lo);
    f.hi = ly(f.hi);
  }
  for (Band& b : s.bands) {
    b.x0 = one(in.log_x, b.x0);
    b.x1 = one(in.log_x, b.x1);
  }
  for (Annotation& a : s.annotations) {
    a.x = one(in.log_x, a.x);
    a.y = one(in.log_y, a.y);
  }
  if (s.y_reference) s.y_reference = one(in.log_y, *s.y_reference);
  if (s.y_include)
    s.y_include =
        Interval{one(in.log_y, s.y_include->lo), one(in.log_y, s.y_include->hi)};
  return s;
}

// The legend: named series, annotations, then the spec's extra entries.
std::vector<LegendEntry> LegendOf(const LinePlotSpec& spec) {
  std::vector<LegendEntry> legend;
  for (const Series& s : spec.series) {
    if (s.name.empty()) continue;
    SeriesStyle style = s.style;
    if (!s.markers) style.marker = MarkerShape::kNone;
    legend.push_back({s.name, style, false, "", s.line});
  }
  for (const Annotation& a : spec.annotations) {
    legend.push_back({a.label, a.style, false, "", false});
  }
  legend.insert(legend.end(), spec.extra_legend.begin(), spec.extra_legend.end());
  return legend;
}

// The ranges of everything drawn: series, annotations, fills, the reference
// line and the range the y axis must include.
std::pair<Interval, Interval> DataRanges(const LinePlotSpec& spec) {
  std::vector<double> xs;
  std::vector<double> ys;
  for (const Series& s : spec.series) {
    xs.insert(xs.end(), s.x.begin(), s.x.end());
    ys.insert(ys.end(), s.y.begin(), s.y.end());
  }
  for (const Annotation& a : spec.annotations) {
    xs.push_back(a.x);
    ys.push_back(a.y);
  }
  for (const FillBetween& f : spec.fills) {
    xs.insert(xs.end(), f.x.begin(), f.x.end());
    ys.insert(ys.end(), f.lo.begin(), f.lo.end());
    ys.insert(ys.end(), f.hi.begin(), f.hi.end());
  }
  if (spec.y_reference) ys.push_back(*spec.y_reference);
  if (spec.y_include) {
    ys.push_back(spec.y_include->lo);
    ys.push_back(spec.y_include->hi);
  }
  return {DataRange(xs), DataRange(ys)};
}

struct AxesLayout {
  Interval xr;
  Interval yr;
  Ticks xt;
  Ticks yt;
};

// Equal scales: one length per unit on both axes, and one tick step, so that
// the grid is made of squares.
AxesLayout EqualScaleAxes(Interval xr, Interval yr, const PlotArea& area) {
  AxesLayout out;
  xr = Pad(xr, 0.05);
  yr = Pad(yr, 0.05);
  const double per_px =
      std::max((xr.hi - xr.lo) / area.width, (yr.hi - yr.lo) / area.height);
  const double xc = (xr.lo + xr.hi) / 2;
  const double yc = (yr.lo + yr.hi) / 2;
  out.xr = {xc - per_px * area.width / 2, xc + per_px * area.width / 2};
  out.yr = {yc - per_px * area.height / 2, yc + per_px * area.height / 2};
  const double step = std::max(NiceTicks(out.xr, 8).step, NiceTicks(out.yr, 6).step);
  out.xt = TicksInside(out.xr, step);
  out.yt = TicksInside(out.yr, step);
  return out;
}

AxesLayout ChooseAxes(const LinePlotSpec& spec, const PlotArea& area) {
  const auto [xr, yr] = DataRanges(spec);
  if (spec.equal_scale) return EqualScaleAxes(xr, yr, area);
  AxesLayout out;
  out.xr = xr;
  // The x axis (time, mostly) ends where the data ends, not at the next
  // round number: ticks inside the data's range.
  out.xt = TicksInside(xr, NiceTicks(xr, 8).step);
  // Padding must not push a range that stops at zero across it (distances).
  Interval padded = Pad(yr, 0.03);
  if (yr.lo >= 0 && padded.lo < 0) padded.lo = 0;
  if (yr.hi <= 0 && padded.hi > 0) padded.hi = 0;
  out.yt = NiceTicks(padded, 5);
  if (spec.log_x) {
    out.xt = DecadeTicks(xr);
    out.xr = out.xt.range;
  }
  if (spec.log_y) out.yt = DecadeTicks(yr);
  out.yr = out.yt.range;
  return out;
}

// Band labels: each centred on its band, on the first of two rows where it
// clears the label before it (narrow bands side by side alternate rows), so
// that no label is left out or drawn over another.
void DrawBands(Svg& svg,
               const LinePlotSpec& spec,
               const PlotArea& area,
               const LinearScale& x) {
  std::array<double, 2> row_end = {-1e300, -1e300};
  for (const Band& b : spec.bands) {
    const double x0 = std::clamp(x(b.x0), area.left, area.right());
    const double x1 = std::clamp(x(b.x1), area.left, area.right());
    if (x1 <= x0) continue;
    svg.Rect(x0, area.top, x1 - x0, area.height, b.css_class);
    if (b.label.empty()) continue;
    const double half = 3.2 * static_cast<double>(b.label.size()) + 1;
    const double centre = (x0 + x1) / 2;
    for (std::size_t row = 0; row < 2; ++row) {
      if (centre - half < row_end[row]) continue;
      svg.Text(centre,
               area.top + 11 + 11 * static_cast<double>(row),
               b.label,
               "band-label",
               "middle");
      row_end[row] = centre + half;
      break;
    }
  }
}

// Each fill as one polygon: along its upper edge, back along its lower one,
// clipped to the y range.
void DrawFills(Svg& svg,
               const LinePlotSpec& spec,
               const LinearScale& x,
               const LinearScale& y,
               const Interval& yr) {
  for (const FillBetween& f : spec.fills) {
    std::vector<double> px, py;
    for (std::size_t i = 0; i < f.x.size(); ++i) {
      if (!std::isfinite(f.x[i]) || !std::isfinite(f.hi[i])) continue;
      px.push_back(x(f.x[i]));
      py.push_back(y(std::min(f.hi[i], yr.hi)));
    }
    for (std::size_t i = f.x.size(); i-- > 0;) {
      if (!std::isfinite(f.x[i]) || !std::isfinite(f.lo[i])) continue;
      px.push_back(x(f.x[i]));
      py.push_back(y(std::max(f.lo[i], yr.lo)));
    }
    svg.Polygon(px, py, f.css_class);
  }
}

// The series (finite points only) and the annotations.
void DrawSeries(Svg& svg,
                const LinePlotSpec& spec,
                const LinearScale& x,
                const LinearScale& y) {
  for (const Series& s : spec.series) {
    std::vector<double> px;
    std::vector<double> py;
    px.reserve(s.x.size());
    py.reserve(s.x.size());
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) continue;
      px.push_back(x(s.x[i]));
      py.push_back(y(s.y[i]));
    }
    svg.OpenGroup("series", s.name);
    if (s.line) svg.Polyline(px, py, s.style);
    if (s.markers) {
      for (std::size_t i = 0; i < px.size(); ++i) {
        svg.Marker(s.style.marker, px[i], py[i], 7, s.style);
      }
    }
    svg.CloseGroup();
  }
  for (const Annotation& a : spec.annotations) {
    svg.OpenGroup("annotation", a.label);
    svg.Marker(a.style.marker, x(a.x), y(a.y), a.size, a.style);
    svg.CloseGroup();
  }
}

}  // namespace

std::string LinePlot(const LinePlotSpec& original) {
  const LinePlotSpec log_spec =
      original.log_x || original.log_y ? ToLogScales(original) : LinePlotSpec{};
  const LinePlotSpec& spec = original.log_x || original.log_y ? log_spec : original;
  const std::vector<LegendEntry> legend = LegendOf(spec);
  const double plot_width = spec.width - kMargins.left - kMargins.right;
  const double legend_height = LegendHeight(legend, plot_width);

  PlotArea area{kMargins.left,
                kMargins.top,
                plot_width,
                spec.height - kMargins.top - kMargins.bottom};
  Svg svg(spec.width,
          spec.height + (legend_height > 0 ? legend_height + kMargins.legend_gap : 0),
          spec.aria_label);
  const AxesLayout axes = ChooseAxes(spec, area);
  const LinearScale x{axes.xr.lo, axes.xr.hi, area.left, area.right()};
  const LinearScale y{axes.yr.lo, axes.yr.hi, area.bottom(), area.top};
  DrawBands(svg, spec, area, x);
  DrawFills(svg, spec, x, y, axes.yr);
  DrawAxes(svg, area, axes.xt, axes.yt, x, y, spec.axes);
  if (spec.y_reference) {
    svg.Line(
        area.left, y(*spec.y_reference), area.right(), y(*spec.y_reference), "reference");
  }
  DrawSeries(svg, spec, x, y);
  if (legend_height > 0) {
    DrawLegend(svg, legend, area.left, spec.height + kMargins.legend_gap, plot_width);
  }
  return svg.Finish();
}

void DecimateMinMax(const std::vector<double>& x,
                    const std::vector<double>& y,
                    std::size_t max_points,
                    std::vector<double>& x_out,
                    std::vector<double>& y_out) {
  x_out.clear();
  y_out.clear();
  const std::size_t n = std::min(x.size(), y.size());
  if (n <= max_points || max_points < 2) {
    x_out.assign(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(n));
    y_out.assign(y.begin(), y.begin() + static_cast<std::ptrdiff_t>(n));
    return;
  }
  const std::size_t buckets = max_points / 2;
  x_out.reserve(2 * buckets);
  y_out.reserve(2 * buckets);
  for (std::size_t b = 0; b < buckets; ++b) {
    const std::size_t begin = b * n / buckets;
    const std::size_t end = (b + 1) * n / buckets;
    if (begin >= end) continue;
    std::size_t lo = begin;
    std::size_t hi = begin;
    for (std::size_t i = begin; i < end; ++i) {
      if (y[i] < y[lo]) lo = i;
      if (y[i] > y[hi]) hi = i;
    }
    const std::size_t first = std::min(lo, hi);
    const std::size_t second = std::max(lo, hi);
    x_out.push_back(x[first]);
    y_out.push_back(y[first]);
    if (second != first) {
      x_out.push_back(x[second]);
      y_out.push_back(y[second]);
    }
  }
}

}  // namespace mpcal::report
