// Bar charts over categories (one bar per category and series, grouped side
// by side), with optional markers over the bars (e.g. cross-validation).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "report/axes.h"
#include "report/svg.h"

namespace mpcal::report {

struct BarSeries {
  std::string name;
  std::vector<double> values;  ///< one per category; non-finite: no bar
  std::string css_class = "bar";
  /// Per-category class overriding css_class where not empty (e.g. a bar of
  /// an excluded position).
  std::vector<std::string> classes;
};

/// Markers drawn over the bars, one per category where present.
struct BarMarkers {
  std::string name;
  std::vector<std::optional<double>> values;
  SeriesStyle style;
};

struct BarChartSpec {
  std::string aria_label;
  AxisLabels axes;
  std::vector<std::string> categories;
  std::vector<BarSeries> bars;
  std::vector<BarMarkers> markers;
  /// Legend entries beyond the series (e.g. the excluded-bar class).
  std::vector<LegendEntry> extra_legend;
  double width = 760.0;
  double height = 260.0;
};

/// The <svg> of the chart. The y axis always includes zero.
std::string BarChart(const BarChartSpec& spec);

}  // namespace mpcal::report
