#include "report/sphere_map.h"

#include <cmath>
#include <numbers>
#include <vector>

#include <fmt/format.h>

#include "mpcal/coverage.h"
#include "report/svg.h"

namespace mpcal::report {

namespace {

constexpr double kDiskGap = 100.0;
constexpr double kTop = 44.0;  // room for the disk titles and "+y"
constexpr double kBottom = 30.0;
// Positions this close to the equator (sin of 3°) are drawn on both disks,
// like the canonical directions on it.
constexpr double kEquatorBand = 0.052;
constexpr double kLegendGap = 8.0;

// Lambert azimuthal equal-area about the pole of the hemisphere: radius
// sqrt(2(1 − |z|)) for a unit vector, √2 on the equator.
Eigen::Vector2d Project(const Eigen::Vector3d& u) {
  const double horizontal = std::hypot(u.x(), u.y());
  if (horizontal < 1e-12) return Eigen::Vector2d::Zero();
  const double r = std::sqrt(std::max(0.0, 2.0 * (1.0 - std::abs(u.z()))));
  return Eigen::Vector2d(u.x(), u.y()) * (r / horizontal);
}

}  // namespace

std::vector<CanonicalDirection> CanonicalCoverage(const std::vector<SpherePoint>& points,
                                                  double tolerance_deg) {
  std::vector<CanonicalDirection> out;
  // Named as the detector names them: by the face, edge or corner of the
  // sensor that points down (one convention everywhere).
  for (const mpcal::CanonicalDirection& c : mpcal::CanonicalDirections()) {
    CanonicalDirection d;
    d.direction = c.direction;
    d.name = c.down;
    out.push_back(d);
  }
  const double cos_tol = std::cos(tolerance_deg * std::numbers::pi / 180.0);
  for (CanonicalDirection& d : out) {
    for (const SpherePoint& p : points) {
      if (!p.used || p.direction.norm() == 0.0) continue;
      if (p.direction.normalized().dot(d.direction) >= cos_tol) d.covered = true;
    }
  }
  return out;
}

std::string SphereMap(const SphereMapSpec& spec) {
  const double radius = (spec.width - kDiskGap - 80.0) / 4.0;
  const double height = kTop + 2 * radius + kBottom;
  const std::vector<LegendEntry> legend = {
      {"position used in the fit",
       {"#0072B2", "", MarkerShape::kCircle, 1.6, false},
       false,
       "",
       false},
      {"excluded position",
       {"#D55E00", "", MarkerShape::kCross, 1.6, false},
       false,
       "",
       false},
      {"canonical direction covered",
       {"#000000", "", MarkerShape::kSquare, 1.6, true},
       false,
       "",
       false},
      {"canonical direction missing",
       {"#D55E00", "", MarkerShape::kTriangle, 1.6, true},
       false,
       "",
       false},
  };
  const double legend_height = LegendHeight(legend, spec.width - 40);
  Svg svg(spec.width, height + legend_height + kLegendGap, spec.aria_label);

  const double scale = radius / std::sqrt(2.0);
  for (int hemisphere = 0; hemisphere < 2; ++hemisphere) {
    const bool upper = hemisphere == 0;
    const double cx = 40.0 + radius + hemisphere * (2 * radius + kDiskGap);
    const double cy = kTop + radius;
    svg.Text(cx,
             16,
             upper ? "z \u2265 0: +z at the centre (z axis up)"
                   : "z < 0: \u2212z at the centre (z axis down)",
             "axis-label",
             "middle");
    svg.Circle(cx, cy, radius, "disk");
    // Guide circle at 45° from the pole.
    svg.Circle(cx, cy, scale * std::sqrt(2.0 * (1.0 - std::sqrt(0.5))), "guide");
    svg.Line(cx - radius, cy, cx + radius, cy, "guide");
    svg.Line(cx, cy - radius, cx, cy + radius, "guide");
    // Axis names outside the rim, clear of the markers on it.
    svg.Text(cx + radius + 12, cy + 4, "+x", "tick-label", "start");
    svg.Text(cx - radius - 12, cy + 4, "\u2212x", "tick-label", "end");
    svg.Text(cx, cy - radius - 12, "+y", "tick-label", "middle");
    svg.Text(cx, cy + radius + 22, "\u2212y", "tick-label", "middle");

    // Directions on the equator belong to both hemispheres.
    auto in_hemisphere = [upper](const Eigen::Vector3d& u, double band) {
      return upper ? u.z() >= -band : u.z() <= band;
    };
    for (const CanonicalDirection& d : spec.canonical) {
      if (!in_hemisphere(d.direction, 1e-9)) continue;
      const Eigen::Vector2d p = Project(d.direction) * scale;
      svg.OpenGroup(d.covered ? "canonical covered" : "canonical missing",
                    fmt::format("{} {}", d.name, d.covered ? "covered" : "missing"));
      svg.Marker(d.covered ? MarkerShape::kSquare : MarkerShape::kTriangle,
                 cx + p.x(),
                 cy - p.y(),
                 15,
                 {d.covered ? "#000000" : "#D55E00", "", MarkerShape::kNone, 1.6, true});
      svg.CloseGroup();
    }
    // Position labels are placed where they clear the labels already drawn
    // on this disk (positions held twice in one orientation, like 1 and 6
    // at the pole, drew "16"): up-right, down-right, up-left, down-left of
    // the marker, then further down.
    struct Box {
      double x0, y0, x1, y1;
    };
    std::vector<Box> placed;
    auto clear = [&placed](const Box& b) {
      for (const Box& o : placed) {
        if (b.x0 < o.x1 && o.x0 < b.x1 && b.y0 < o.y1 && o.y0 < b.y1) return false;
      }
      return true;
    };
    for (const SpherePoint& point : spec.points) {
      if (point.direction.norm() == 0.0) continue;
      const Eigen::Vector3d u = point.direction.normalized();
      if (!in_hemisphere(u, kEquatorBand)) continue;
      const Eigen::Vector2d p = Project(u) * scale;
      const SeriesStyle style =
          point.used ? SeriesStyle{"#0072B2", "", MarkerShape::kCircle, 1.6, false}
                     : SeriesStyle{"#D55E00", "", MarkerShape::kCross, 1.6, false};
      svg.OpenGroup(
          "position",
          fmt::format("position {}{}", point.label, point.used ? "" : " (excluded)"));
      svg.Marker(style.marker, cx + p.x(), cy - p.y(), 7, style);
      if (!point.label.empty()) {
        const double w = 6.0 * static_cast<double>(point.label.size());
        const double x = cx + p.x();
        const double y = cy - p.y();
        // (left edge, baseline) candidates; the box is 9 units tall.
        const double candidates[][2] = {{x + 5, y - 5},
                                        {x + 5, y + 12},
                                        {x - 5 - w, y - 5},
                                        {x - 5 - w, y + 12},
                                        {x + 5, y + 22},
                                        {x - 5 - w, y + 22}};
        Box box{x + 5, y - 14, x + 5 + w, y - 5};
        for (const auto& c : candidates) {
          const Box b{c[0], c[1] - 9, c[0] + w, c[1]};
          if (clear(b)) {
            box = b;
            break;
          }
        }
        placed.push_back(box);
        svg.Text(box.x0, box.y1, point.label, "point-label", "start");
      }
      svg.CloseGroup();
    }
  }
  DrawLegend(svg, legend, 40, height + kLegendGap, spec.width - 40);
  return svg.Finish();
}

}  // namespace mpcal::report
