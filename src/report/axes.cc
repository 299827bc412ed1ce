#include "report/axes.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

namespace mpcal::report {

Interval DataRange(const std::vector<double>& v, const std::vector<double>& more) {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -lo;
  for (const auto* values : {&v, &more}) {
    for (double x : *values) {
      if (!std::isfinite(x)) continue;
      lo = std::min(lo, x);
      hi = std::max(hi, x);
    }
  }
  if (lo > hi) return {0.0, 1.0};
  if (hi - lo <= 1e-12 * std::max(1.0, std::abs(lo))) {
    const double half = std::max(std::abs(lo) * 0.05, 1e-9);
    return {lo - half, hi + half};
  }
  return {lo, hi};
}

Interval Pad(Interval r, double fraction) {
  const double d = (r.hi - r.lo) * fraction;
  return {r.lo - d, r.hi + d};
}

Ticks NiceTicks(Interval r, int target) {
  Ticks t;
  const double span = r.hi - r.lo;
  const double raw = span / std::max(1, target);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double residual = raw / magnitude;
  const double nice = residual < 1.5 ? 1 : residual < 3.5 ? 2 : residual < 7.5 ? 5 : 10;
  t.step = nice * magnitude;
  const double first = std::floor(r.lo / t.step + 1e-9) * t.step;
  const double last = std::ceil(r.hi / t.step - 1e-9) * t.step;
  t.range = {first, last};
  const int n = static_cast<int>(std::lround((last - first) / t.step));
  for (int i = 0; i <= n; ++i) {
    double v = first + i * t.step;
    if (std::abs(v) < t.step * 1e-9) v = 0.0;  // no "-0"
    t.values.push_back(v);
  }
  return t;
}

std::string FormatTick(double v, double step) {
  const int decimals =
      std::clamp(static_cast<int>(-std::floor(std::log10(step) + 1e-9)), 0, 9);
  if (std::abs(v) >= 1e6 || (std::abs(v) < 1e-4 && v != 0.0 && decimals > 6)) {
    return fmt::format("{:.2g}", v);
  }
  return fmt::format("{:.{}f}", v, decimals);
}

namespace {

std::string TickLabel(const Ticks& t, std::size_t i) {
  return i < t.labels.size() ? t.labels[i] : FormatTick(t.values[i], t.step);
}

}  // namespace

Ticks DecadeTicks(Interval r) {
  static const char* const kSuperscript[] = {"\u2070",
                                             "\u00b9",
                                             "\u00b2",
                                             "\u00b3",
                                             "\u2074",
                                             "\u2075",
                                             "\u2076",
                                             "\u2077",
                                             "\u2078",
                                             "\u2079"};
  Ticks t;
  t.step = 1.0;
  t.range = {std::floor(r.lo + 1e-9), std::ceil(r.hi - 1e-9)};
  if (t.range.hi <= t.range.lo) t.range.hi = t.range.lo + 1.0;
  for (double d = t.range.lo; d <= t.range.hi + 1e-9; d += 1.0) {
    t.values.push_back(d);
    const int n = static_cast<int>(std::lround(d));
    std::string label = "10";
    if (n < 0) label += "\u207b";
    for (const char c : std::to_string(std::abs(n))) label += kSuperscript[c - '0'];
    t.labels.push_back(label);
  }
  return t;
}

void DrawAxes(Svg& svg,
              const PlotArea& area,
              const Ticks& x_ticks,
              const Ticks& y_ticks,
              const LinearScale& x,
              const LinearScale& y,
              const AxisLabels& labels) {
  svg.OpenGroup("axes");
  std::size_t i_x = 0, i_y = 0;
  for (double v : x_ticks.values) {
    const double px = x(v);
    svg.Line(px, area.top, px, area.bottom(), "grid");
    svg.Line(px, area.bottom(), px, area.bottom() + 4, "tick");
    svg.Text(px, area.bottom() + 17, TickLabel(x_ticks, i_x++), "tick-label", "middle");
  }
  for (double v : y_ticks.values) {
    const double py = y(v);
    svg.Line(area.left, py, area.right(), py, "grid");
    svg.Line(area.left - 4, py, area.left, py, "tick");
    svg.Text(area.left - 7, py + 4, TickLabel(y_ticks, i_y++), "tick-label", "end");
  }
  svg.Rect(area.left, area.top, area.width, area.height, "frame");
  svg.Text(
      area.left + area.width / 2, area.bottom() + 36, labels.x, "axis-label", "middle");
  const double ly = area.top + area.height / 2;
  svg.Text(area.left - 52, ly, labels.y, "axis-label", "middle", -90);
  svg.CloseGroup();
}

}  // namespace mpcal::report
