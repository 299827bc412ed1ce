#include "report/sphere_map.h"

#include <array>
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

namespace {

std::vector<LegendEntry> SphereLegend() {
  return {
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
}

// One hemisphere's disk: centre (cx, cy), `radius` in SVG units, `scale`
// from the projection to SVG units.
struct Disk {
  bool upper = true;
  double cx = 0.0;
  double cy = 0.0;
  double radius = 0.0;
  double scale = 0.0;

  // Directions on the equator belong to both hemispheres.
  bool Holds(const Eigen::Vector3d& u, double band) const {
    return upper ? u.z() >= -band : u.z() <= band;
  }
};

void DrawDisk(Svg& svg, const Disk& d) {
  svg.Text(d.cx,
           16,
           d.upper ? "z \u2265 0: +z at the centre (z axis up)"
                   : "z < 0: \u2212z at the centre (z axis down)",
           "axis-label",
           "middle");
  svg.Circle(d.cx, d.cy, d.radius, "disk");
  // Guide circle at 45° from the pole.
  svg.Circle(d.cx, d.cy, d.scale * std::sqrt(2.0 * (1.0 - std::sqrt(0.5))), "guide");
  svg.Line(d.cx - d.radius, d.cy, d.cx + d.radius, d.cy, "guide");
  svg.Line(d.cx, d.cy - d.radius, d.cx, d.cy + d.radius, "guide");
  // Axis names outside the rim, clear of the markers on it.
  svg.Text(d.cx + d.radius + 12, d.cy + 4, "+x", "tick-label", "start");
  svg.Text(d.cx - d.radius - 12, d.cy + 4, "\u2212x", "tick-label", "end");
  svg.Text(d.cx, d.cy - d.radius - 12, "+y", "tick-label", "middle");
  svg.Text(d.cx, d.cy + d.radius + 22, "\u2212y", "tick-label", "middle");
}

void DrawCanonical(Svg& svg, const SphereMapSpec& spec, const Disk& disk) {
  for (const CanonicalDirection& d : spec.canonical) {
    if (!disk.Holds(d.direction, 1e-9)) continue;
    const Eigen::Vector2d p = Project(d.direction) * disk.scale;
    svg.OpenGroup(d.covered ? "canonical covered" : "canonical missing",
                  fmt::format("{} {}", d.name, d.covered ? "covered" : "missing"));
    svg.Marker(d.covered ? MarkerShape::kSquare : MarkerShape::kTriangle,
               disk.cx + p.x(),
               disk.cy - p.y(),
               15,
               {d.covered ? "#000000" : "#D55E00", "", MarkerShape::kNone, 1.6, true});
    svg.CloseGroup();
  }
}

// Position labels are placed where they clear the labels already drawn on
// this disk (positions held twice in one orientation, like 1 and 6 at the
// pole, drew "16"): up-right, down-right, up-left, down-left of the marker,
// then further down.
class LabelPlacer {
 public:
  struct Box {
    double x0, y0, x1, y1;
  };

  // The box (9 units tall) for a label `w` wide at the marker (x, y).
  Box Place(double x, double y, double w) {
    // (left edge, baseline) candidates.
    const std::array<std::array<double, 2>, 6> candidates = {{{x + 5, y - 5},
                                                              {x + 5, y + 12},
                                                              {x - 5 - w, y - 5},
                                                              {x - 5 - w, y + 12},
                                                              {x + 5, y + 22},
                                                              {x - 5 - w, y + 22}}};
    Box box{x + 5, y - 14, x + 5 + w, y - 5};
    for (const auto& c : candidates) {
      const Box b{c[0], c[1] - 9, c[0] + w, c[1]};
      if (Clear(b)) {
        box = b;
        break;
      }
    }
    placed_.push_back(box);
    return box;
  }

 private:
  bool Clear(const Box& b) const {
    for (const Box& o : placed_) {
      if (b.x0 < o.x1 && o.x0 < b.x1 && b.y0 < o.y1 && o.y0 < b.y1) return false;
    }
    return true;
  }
  std::vector<Box> placed_;
};

void DrawPositions(Svg& svg, const SphereMapSpec& spec, const Disk& disk) {
  LabelPlacer labels;
  for (const SpherePoint& point : spec.points) {
    if (point.direction.norm() == 0.0) continue;
    const Eigen::Vector3d u = point.direction.normalized();
    if (!disk.Holds(u, kEquatorBand)) continue;
    const Eigen::Vector2d p = Project(u) * disk.scale;
    const SeriesStyle style =
        point.used ? SeriesStyle{"#0072B2", "", MarkerShape::kCircle, 1.6, false}
                   : SeriesStyle{"#D55E00", "", MarkerShape::kCross, 1.6, false};
    svg.OpenGroup(
        "position",
        fmt::format("position {}{}", point.label, point.used ? "" : " (excluded)"));
    svg.Marker(style.marker, disk.cx + p.x(), disk.cy - p.y(), 7, style);
    if (!point.label.empty()) {
      const double w = 6.0 * static_cast<double>(point.label.size());
      const LabelPlacer::Box box = labels.Place(disk.cx + p.x(), disk.cy - p.y(), w);
      svg.Text(box.x0, box.y1, point.label, "point-label", "start");
    }
    svg.CloseGroup();
  }
}

}  // namespace

std::string SphereMap(const SphereMapSpec& spec) {
  const double radius = (spec.width - kDiskGap - 80.0) / 4.0;
  const double height = kTop + 2 * radius + kBottom;
  const std::vector<LegendEntry> legend = SphereLegend();
  const double legend_height = LegendHeight(legend, spec.width - 40);
  Svg svg(spec.width, height + legend_height + kLegendGap, spec.aria_label);
  for (int hemisphere = 0; hemisphere < 2; ++hemisphere) {
    Disk disk;
    disk.upper = hemisphere == 0;
    disk.radius = radius;
    disk.scale = radius / std::sqrt(2.0);
    disk.cx = 40.0 + radius + hemisphere * (2 * radius + kDiskGap);
    disk.cy = kTop + radius;
    DrawDisk(svg, disk);
    DrawCanonical(svg, spec, disk);
    DrawPositions(svg, spec, disk);
  }
  DrawLegend(svg, legend, 40, height + kLegendGap, spec.width - 40);
  return svg.Finish();
}

}  // namespace mpcal::report
