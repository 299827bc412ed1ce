// SVG primitives for the report's figures: an element builder that escapes
// every text it is given, series styles that stay distinct in greyscale
// (dash pattern and marker shape, not only colour), markers and legends.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace mpcal::report {

/// Escapes & < > " ' for text and attribute values (HTML and SVG alike).
std::string EscapeXml(std::string_view text);

/// A coordinate with two decimals: enough at screen scale, short in the file.
std::string Coord(double v);

enum class MarkerShape { kNone, kCircle, kSquare, kTriangle, kDiamond, kCross };

/// How one data series is drawn. Series differ by dash and marker as well as
/// by colour, so that a greyscale print keeps them apart.
struct SeriesStyle {
  std::string color = "#000000";
  std::string dash;  ///< SVG stroke-dasharray; empty = solid
  MarkerShape marker = MarkerShape::kNone;
  double width = 1.6;
  bool hollow_marker = false;
};

/// The i-th of the report's standard styles (Okabe-Ito colours, which are
/// safe for colour-blind readers, with distinct dashes and markers).
SeriesStyle StandardStyle(int i);

/// Builds one <svg> element. Sizes are user units; the element scales to the
/// page width through its viewBox.
class Svg {
 public:
  Svg(double width, double height, std::string_view label);

  double width() const { return width_; }
  double height() const { return height_; }

  void Line(double x1,
            double y1,
            double x2,
            double y2,
            std::string_view cls,
            std::string_view style = "");
  /// A polyline through (x[i], y[i]); nothing for fewer than two points.
  void Polyline(const std::vector<double>& x,
                const std::vector<double>& y,
                const SeriesStyle& style);
  void Rect(double x,
            double y,
            double w,
            double h,
            std::string_view cls,
            std::string_view style = "");
  /// A closed, filled polygon through (x[i], y[i]) (confidence bands).
  void Polygon(const std::vector<double>& x,
               const std::vector<double>& y,
               std::string_view cls);
  void Circle(
      double cx, double cy, double r, std::string_view cls, std::string_view style = "");
  /// `anchor`: start, middle or end; `rotate_deg` about (x, y).
  void Text(double x,
            double y,
            std::string_view text,
            std::string_view cls,
            std::string_view anchor = "start",
            double rotate_deg = 0.0);
  void Marker(
      MarkerShape shape, double x, double y, double size, const SeriesStyle& style);
  /// A tooltip for the element opened next with OpenGroup.
  void OpenGroup(std::string_view cls, std::string_view title = "");
  void CloseGroup();

  /// The finished element; the builder is left empty.
  std::string Finish();

 private:
  double width_;
  double height_;
  int open_groups_ = 0;
  std::string body_;
};

/// One entry of a legend: a line sample (with its marker) or a filled patch.
struct LegendEntry {
  std::string label;
  SeriesStyle style;
  bool patch = false;       ///< draw a filled box instead of a line
  std::string patch_class;  ///< CSS class of the patch
  bool line = true;         ///< false: the marker alone (scatter series)
};

/// Height DrawLegend will take for these entries (0 for none).
double LegendHeight(const std::vector<LegendEntry>& entries, double max_width);

/// Draws a legend in one row starting at (x, y) (baseline of the text);
/// wraps to a new row when `max_width` is exceeded. Returns its height.
double DrawLegend(Svg& svg,
                  const std::vector<LegendEntry>& entries,
                  double x,
                  double y,
                  double max_width);

}  // namespace mpcal::report
