// Dot plots: one row per item (e.g. a model parameter), points along a
// common x axis marked by group (e.g. trial), and an optional shaded band per
// row (e.g. ±1σ). The scatter chart of the repeatability section.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "report/axes.h"
#include "report/svg.h"

namespace mpcal::report {

struct DotRow {
  std::string label;
  /// One value per group; non-finite: not drawn.
  std::vector<double> values;
  std::optional<Interval> band;
};

struct DotPlotSpec {
  std::string aria_label;
  std::string x_label;  ///< with its unit
  std::vector<DotRow> rows;
  /// Legend names of the groups (markers use StandardStyle(group)).
  std::vector<std::string> groups;
  std::string band_legend;  ///< legend text of the bands; empty: none
  double width = 760.0;
  double row_height = 26.0;
  /// Forces x to include this range.
  std::optional<Interval> x_include;
  /// When set, x is limited to ±clip_abs; values beyond are drawn at the
  /// edge, pointing outwards, with their value written beside them.
  std::optional<double> clip_abs;
};

/// The <svg> of the plot.
std::string DotPlot(const DotPlotSpec& spec);

}  // namespace mpcal::report
