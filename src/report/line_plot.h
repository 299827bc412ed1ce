// Line and scatter plots: series of (x, y) drawn as lines and/or markers,
// optional shaded x-intervals (static positions), point annotations, and an
// equal-scale mode for maps (east-north paths).
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "report/axes.h"
#include "report/svg.h"

namespace mpcal::report {

struct Series {
  std::string name;  ///< legend entry; empty: not in the legend
  std::vector<double> x;
  std::vector<double> y;
  SeriesStyle style;
  bool line = true;      ///< join the points
  bool markers = false;  ///< a marker at every point (scatter)
};

/// A shaded stretch of the x axis with an optional label above it.
struct Band {
  double x0 = 0.0;
  double x1 = 0.0;
  std::string label;
  std::string css_class = "band";
};

/// A single marked point with a text label (start, end, ...).
struct Annotation {
  double x = 0.0;
  double y = 0.0;
  std::string label;
  SeriesStyle style;
  double size = 11.0;
};

/// A shaded band between two curves over the same x (a confidence band).
struct FillBetween {
  std::vector<double> x;
  std::vector<double> lo;
  std::vector<double> hi;
  std::string css_class = "band";
};

struct LinePlotSpec {
  std::string aria_label;
  AxisLabels axes;
  std::vector<Series> series;
  std::vector<Band> bands;
  std::vector<Annotation> annotations;
  /// Legend entries for the bands (patches), after the series.
  std::vector<LegendEntry> extra_legend;
  double width = 760.0;
  double height = 320.0;
  /// One data unit is as long on x as on y (maps); widens the shorter range.
  bool equal_scale = false;
  /// A horizontal reference line (e.g. zero, 1σ).
  std::optional<double> y_reference;
  /// Forces y to include this range.
  std::optional<Interval> y_include;
  /// Logarithmic axes (positive data only; ticks at each decade). Bands,
  /// the reference line and y_include are then in data units too.
  bool log_x = false;
  bool log_y = false;
  /// Shaded bands, drawn under the series.
  std::vector<FillBetween> fills;
};

/// The <svg> of the plot.
std::string LinePlot(const LinePlotSpec& spec);

/// Keeps the shape of a long signal in about `max_points` points: for each of
/// max_points/2 buckets, the minimum and the maximum in time order, so spikes
/// survive. Shorter inputs are returned unchanged.
void DecimateMinMax(const std::vector<double>& x,
                    const std::vector<double>& y,
                    std::size_t max_points,
                    std::vector<double>& x_out,
                    std::vector<double>& y_out);

}  // namespace mpcal::report
