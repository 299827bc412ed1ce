#include "report/svg.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>

namespace mpcal::report {

std::string EscapeXml(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string Coord(double v) {
  // Non-finite coordinates would make the element invalid; callers filter
  // data, this only keeps a stray one from breaking the page.
  if (!std::isfinite(v)) return "0";
  std::string s = fmt::format("{:.2f}", v);
  while (s.back() == '0') s.pop_back();
  if (s.back() == '.') s.pop_back();
  if (s == "-0") s = "0";
  return s;
}

SeriesStyle StandardStyle(int i) {
  // Okabe-Ito: blue, vermillion, bluish green, reddish purple, black, orange.
  static const std::array<SeriesStyle, 6> kStyles = {{
      {"#0072B2", "", MarkerShape::kCircle, 1.6, false},
      {"#D55E00", "7 4", MarkerShape::kSquare, 1.6, false},
      {"#009E73", "2 3", MarkerShape::kTriangle, 1.8, false},
      {"#CC79A7", "9 3 2 3", MarkerShape::kDiamond, 1.6, false},
      {"#000000", "", MarkerShape::kCross, 1.2, false},
      {"#E69F00", "4 2", MarkerShape::kCircle, 1.6, true},
  }};
  return kStyles[static_cast<std::size_t>(i) % kStyles.size()];
}

Svg::Svg(double width, double height, std::string_view label)
    : width_(width), height_(height) {
  // No xmlns: inline SVG in HTML needs none, and the page must not contain a
  // single URL.
  body_ = fmt::format(
      "<svg viewBox=\"0 0 {} {}\" role=\"img\" aria-label=\"{}\" "
      "preserveAspectRatio=\"xMidYMid meet\">\n",
      Coord(width),
      Coord(height),
      EscapeXml(label));
}

namespace {

std::string StyleAttr(std::string_view style) {
  return style.empty() ? std::string() : fmt::format(" style=\"{}\"", style);
}

std::string ClassAttr(std::string_view cls) {
  return cls.empty() ? std::string() : fmt::format(" class=\"{}\"", cls);
}

std::string StrokeStyle(const SeriesStyle& s) {
  std::string out = fmt::format("fill:none;stroke:{};stroke-width:{}", s.color, s.width);
  if (!s.dash.empty()) out += fmt::format(";stroke-dasharray:{}", s.dash);
  return out;
}

}  // namespace

void Svg::Line(double x1,
               double y1,
               double x2,
               double y2,
               std::string_view cls,
               std::string_view style) {
  body_ += fmt::format("<line x1=\"{}\" y1=\"{}\" x2=\"{}\" y2=\"{}\"{}{}/>\n",
                       Coord(x1),
                       Coord(y1),
                       Coord(x2),
                       Coord(y2),
                       ClassAttr(cls),
                       StyleAttr(style));
}

void Svg::Polyline(const std::vector<double>& x,
                   const std::vector<double>& y,
                   const SeriesStyle& style) {
  // The pairs given: a longer x or y is not read past the other's end.
  const std::size_t n = std::min(x.size(), y.size());
  if (n < 2) return;
  std::string points;
  points.reserve(n * 14);
  for (std::size_t i = 0; i < n; ++i) {
    if (i) points += ' ';
    points += Coord(x[i]);
    points += ',';
    points += Coord(y[i]);
  }
  body_ += fmt::format("<polyline points=\"{}\" style=\"{};stroke-linejoin:round\"/>\n",
                       points,
                       StrokeStyle(style));
}

void Svg::Rect(double x,
               double y,
               double w,
               double h,
               std::string_view cls,
               std::string_view style) {
  body_ += fmt::format("<rect x=\"{}\" y=\"{}\" width=\"{}\" height=\"{}\"{}{}/>\n",
                       Coord(x),
                       Coord(y),
                       Coord(std::max(w, 0.0)),
                       Coord(std::max(h, 0.0)),
                       ClassAttr(cls),
                       StyleAttr(style));
}

void Svg::Polygon(const std::vector<double>& x,
                  const std::vector<double>& y,
                  std::string_view cls) {
  // The pairs given: a longer x or y is not read past the other's end.
  const std::size_t n = std::min(x.size(), y.size());
  if (n < 3) return;
  std::string points;
  for (std::size_t i = 0; i < n; ++i) {
    if (i) points += ' ';
    points += Coord(x[i]);
    points += ',';
    points += Coord(y[i]);
  }
  body_ += fmt::format("<polygon points=\"{}\"{}/>\n", points, ClassAttr(cls));
}

void Svg::Circle(
    double cx, double cy, double r, std::string_view cls, std::string_view style) {
  body_ += fmt::format("<circle cx=\"{}\" cy=\"{}\" r=\"{}\"{}{}/>\n",
                       Coord(cx),
                       Coord(cy),
                       Coord(r),
                       ClassAttr(cls),
                       StyleAttr(style));
}

void Svg::Text(double x,
               double y,
               std::string_view text,
               std::string_view cls,
               std::string_view anchor,
               double rotate_deg) {
  std::string transform;
  if (rotate_deg != 0.0) {
    transform = fmt::format(
        " transform=\"rotate({} {} {})\"", Coord(rotate_deg), Coord(x), Coord(y));
  }
  body_ += fmt::format("<text x=\"{}\" y=\"{}\" text-anchor=\"{}\"{}{}>{}</text>\n",
                       Coord(x),
                       Coord(y),
                       anchor,
                       ClassAttr(cls),
                       transform,
                       EscapeXml(text));
}

void Svg::Marker(
    MarkerShape shape, double x, double y, double size, const SeriesStyle& style) {
  const double h = size / 2;
  const std::string fill = style.hollow_marker ? "none" : style.color;
  const std::string paint =
      fmt::format("fill:{};stroke:{};stroke-width:1.2", fill, style.color);
  switch (shape) {
    case MarkerShape::kNone:
      return;
    case MarkerShape::kCircle:
      Circle(x, y, h, "", paint);
      return;
    case MarkerShape::kSquare:
      Rect(x - h * 0.9, y - h * 0.9, h * 1.8, h * 1.8, "", paint);
      return;
    case MarkerShape::kTriangle:
      body_ += fmt::format("<polygon points=\"{},{} {},{} {},{}\" style=\"{}\"/>\n",
                           Coord(x),
                           Coord(y - h * 1.15),
                           Coord(x - h * 1.1),
                           Coord(y + h * 0.8),
                           Coord(x + h * 1.1),
                           Coord(y + h * 0.8),
                           paint);
      return;
    case MarkerShape::kDiamond:
      body_ += fmt::format("<polygon points=\"{},{} {},{} {},{} {},{}\" style=\"{}\"/>\n",
                           Coord(x),
                           Coord(y - h * 1.2),
                           Coord(x + h),
                           Coord(y),
                           Coord(x),
                           Coord(y + h * 1.2),
                           Coord(x - h),
                           Coord(y),
                           paint);
      return;
    case MarkerShape::kCross: {
      const std::string stroke = fmt::format("stroke:{};stroke-width:1.8", style.color);
      Line(x - h, y - h, x + h, y + h, "", stroke);
      Line(x - h, y + h, x + h, y - h, "", stroke);
      return;
    }
  }
}

void Svg::OpenGroup(std::string_view cls, std::string_view title) {
  body_ += fmt::format("<g{}>", ClassAttr(cls));
  if (!title.empty()) body_ += fmt::format("<title>{}</title>", EscapeXml(title));
  body_ += '\n';
  ++open_groups_;
}

void Svg::CloseGroup() {
  if (open_groups_ == 0) return;  // nothing open: no stray </g>
  body_ += "</g>\n";
  --open_groups_;
}

std::string Svg::Finish() {
  while (open_groups_ > 0) CloseGroup();  // well-formed whatever the caller did
  std::string out = std::move(body_);
  out += "</svg>\n";
  body_.clear();
  return out;
}

namespace {

constexpr double kLegendRowHeight = 18.0;
constexpr double kLegendSampleWidth = 30.0;

double LegendEntryWidth(const LegendEntry& e) {
  constexpr double kCharWidth = 6.6;  // average glyph advance at 12 px
  return kLegendSampleWidth + 6 + kCharWidth * static_cast<double>(e.label.size()) + 18;
}

}  // namespace

double LegendHeight(const std::vector<LegendEntry>& entries, double max_width) {
  if (entries.empty()) return 0.0;
  double cx = 0.0;
  int rows = 1;
  for (const LegendEntry& e : entries) {
    const double w = LegendEntryWidth(e);
    if (cx > 0 && cx + w > max_width) {
      cx = 0;
      ++rows;
    }
    cx += w;
  }
  return rows * kLegendRowHeight;
}

double DrawLegend(Svg& svg,
                  const std::vector<LegendEntry>& entries,
                  double x,
                  double y,
                  double max_width) {
  double cx = x;
  double cy = y;
  for (const LegendEntry& e : entries) {
    const double w = LegendEntryWidth(e);
    if (cx > x && cx + w > x + max_width) {
      cx = x;
      cy += kLegendRowHeight;
    }
    if (e.patch) {
      svg.Rect(cx, cy - 10, kLegendSampleWidth, 11, e.patch_class);
    } else {
      if (e.line) {
        svg.Line(cx,
                 cy - 4,
                 cx + kLegendSampleWidth,
                 cy - 4,
                 "",
                 fmt::format("stroke:{};stroke-width:{}{}",
                             e.style.color,
                             e.style.width,
                             e.style.dash.empty() ? std::string()
                                                  : ";stroke-dasharray:" + e.style.dash));
      }
      svg.Marker(e.style.marker, cx + kLegendSampleWidth / 2, cy - 4, 7, e.style);
    }
    svg.Text(cx + kLegendSampleWidth + 6, cy, e.label, "legend");
    cx += w;
  }
  return entries.empty() ? 0.0 : cy - y + kLegendRowHeight;
}

}  // namespace mpcal::report
