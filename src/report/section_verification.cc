#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "report/html.h"
#include "report/line_plot.h"
#include "report/sections.h"

namespace mpcal::report {

namespace {

using Metrics = VerificationSummary::Metrics;

constexpr std::size_t kMaxPathPoints = 3000;

// The same look for a path in every figure: raw dashed, corrected dotted.
const SeriesStyle kRawStyle{"#D55E00", "7 4", MarkerShape::kTriangle, 1.8, true};
const SeriesStyle kCorrectedStyle{"#0072B2", "2 3", MarkerShape::kDiamond, 2.2, true};

std::string Metres(const std::optional<double>& v) {
  return v ? Fixed(*v, 2) : std::string("\u2014");
}

std::string MetricsTable(const VerificationSummary& v) {
  const bool corrected = v.corrected.has_value();
  std::vector<std::string> header = {"", "reference (GNSS)", "raw"};
  if (corrected) header.push_back("corrected");
  Table t;
  t.Header(header);
  auto row = [&](const char* label, auto field) {
    std::vector<std::string> cells = {
        label, Metres(field(v.reference)), Metres(field(v.raw))};
    if (corrected) cells.push_back(Metres(field(*v.corrected)));
    t.Row(cells);
  };
  row("start-to-end distance (m)",
      [](const Metrics& m) { return std::optional<double>(m.start_end_distance_m); });
  row("horizontal RMS distance to the reference (m)",
      [](const Metrics& m) { return m.horizontal_rms_m; });
  row("horizontal maximum distance to the reference (m)",
      [](const Metrics& m) { return m.horizontal_max_m; });
  row("path length (m)", [](const Metrics& m) { return m.path_length_m; });
  return t.Finish();
}

Series PathSeries(const std::string& name,
                  const EastNorthPath& p,
                  const SeriesStyle& style) {
  Series s;
  s.name = name;
  s.style = style;
  // Decimate by stride: a path has no spikes to keep, and both coordinates
  // must come from the same samples.
  const std::size_t n = std::min(p.east_m.size(), p.north_m.size());
  const std::size_t stride = std::max<std::size_t>(1, n / kMaxPathPoints);
  for (std::size_t i = 0; i < n; i += stride) {
    s.x.push_back(p.east_m[i]);
    s.y.push_back(p.north_m[i]);
  }
  if (n > 0 && (n - 1) % stride != 0) {
    s.x.push_back(p.east_m[n - 1]);
    s.y.push_back(p.north_m[n - 1]);
  }
  return s;
}

// Horizontal distance from each sample of `path` to the reference at the
// same time (linear interpolation); samples outside the reference's time
// span are skipped.
Series ErrorSeries(const std::string& name,
                   const EastNorthPath& path,
                   const EastNorthPath& ref,
                   double t0,
                   const SeriesStyle& style) {
  Series s;
  s.name = name;
  s.style = style;
  if (ref.time_s.size() < 2) return s;
  const std::size_t n = path.time_s.size();
  const std::size_t stride = std::max<std::size_t>(1, n / kMaxPathPoints);
  for (std::size_t i = 0; i < n; i += stride) {
    const double t = path.time_s[i];
    const auto it = std::lower_bound(ref.time_s.begin(), ref.time_s.end(), t);
    if (it == ref.time_s.end() || (it == ref.time_s.begin() && *it != t)) continue;
    const std::size_t j = static_cast<std::size_t>(it - ref.time_s.begin());
    const std::size_t j0 = j == 0 ? 0 : j - 1;
    const double span = ref.time_s[j] - ref.time_s[j0];
    const double w = span > 0 ? (t - ref.time_s[j0]) / span : 0.0;
    const double e = ref.east_m[j0] + w * (ref.east_m[j] - ref.east_m[j0]);
    const double nn = ref.north_m[j0] + w * (ref.north_m[j] - ref.north_m[j0]);
    s.x.push_back(t - t0);
    s.y.push_back(std::hypot(path.east_m[i] - e, path.north_m[i] - nn));
  }
  return s;
}

// Largest east or north extent of a path (m); 0 for none.
double Extent(const std::optional<EastNorthPath>& p) {
  if (!p || p->east_m.empty()) return 0.0;
  const auto [e0, e1] = std::minmax_element(p->east_m.begin(), p->east_m.end());
  const auto [n0, n1] = std::minmax_element(p->north_m.begin(), p->north_m.end());
  return std::max(*e1 - *e0, *n1 - *n0);
}

// The paths in east-north; without the raw one when `with_raw` is false (the
// zoom on the reference when the raw path wandered far off).
std::string PathFigure(const VerificationSummary& v, bool with_raw = true) {
  LinePlotSpec spec;
  spec.aria_label = with_raw ? "Reference, raw and corrected paths, east against north"
                             : "Reference and corrected paths, east against north";
  spec.axes = {"east (m)", "north (m)"};
  spec.equal_scale = true;
  spec.height = 520;
  const SeriesStyle ref_style{"#000000", "", MarkerShape::kSquare, 2.2, true};
  const SeriesStyle& raw_style = kRawStyle;
  const SeriesStyle& cor_style = kCorrectedStyle;
  const EastNorthPath* first = nullptr;
  auto add = [&](const std::optional<EastNorthPath>& p,
                 const std::string& name,
                 const SeriesStyle& style,
                 double distance) {
    if (!p || p->east_m.empty()) return;
    if (!first) first = &*p;
    spec.series.push_back(PathSeries(name, *p, style));
    spec.annotations.push_back(
        {p->east_m.back(),
         p->north_m.back(),
         fmt::format("end, {} ({:.2f} m from start)", name, distance),
         style,
         11});
  };
  add(v.reference_path, "reference", ref_style, v.reference.start_end_distance_m);
  if (with_raw) add(v.raw_path, "raw", raw_style, v.raw.start_end_distance_m);
  if (v.corrected) {
    add(v.corrected_path, "corrected", cor_style, v.corrected->start_end_distance_m);
  }
  if (!first) return "";
  // The integrated paths are placed at the reference's first point: one
  // start, drawn last as a ring so that an end marker on it stays visible.
  spec.annotations.push_back({first->east_m.front(),
                              first->north_m.front(),
                              "start",
                              {"#009E73", "", MarkerShape::kCircle, 2.2, true},
                              20});
  if (!with_raw) {
    return Figure(LinePlot(spec),
                  "Zoom on the reference: the same without the raw path, which ends too "
                  "far away to show the others at a legible scale.");
  }
  return Figure(
      LinePlot(spec),
      "The GNSS reference and the paths integrated from the raw and the "
      "corrected accelerations, in the local east-north frame at the first fix "
      "(equal scales). The integrated paths start at the reference's first "
      "point along its initial heading; how far each ends from its start is the "
      "figure of merit of the paper's Table 7.");
}

std::string ErrorFigure(const VerificationSummary& v) {
  if (!v.reference_path || v.reference_path->time_s.size() < 2) return "";
  const double t0 = v.reference_path->time_s.front();
  LinePlotSpec spec;
  spec.aria_label = "Horizontal distance to the reference against time";
  spec.axes = {"time since the first reference fix (s)", "distance to reference (m)"};
  spec.y_include = Interval{0.0, 0.0};
  spec.height = 300;
  if (v.raw_path) {
    spec.series.push_back(
        ErrorSeries("raw", *v.raw_path, *v.reference_path, t0, kRawStyle));
  }
  if (v.corrected_path) {
    spec.series.push_back(ErrorSeries(
        "corrected", *v.corrected_path, *v.reference_path, t0, kCorrectedStyle));
  }
  bool any = false;
  for (const Series& s : spec.series) any |= s.x.size() >= 2;
  if (!any) {
    return Paragraph(
        "The integrated paths and the reference do not overlap in time: "
        "no error against time.",
        "note");
  }
  return Figure(LinePlot(spec),
                "Horizontal distance from each integrated path to the reference at the "
                "same time (reference interpolated linearly).");
}

// No paths: said as a fact; what would give them (the trajectories of the
// verification) in the caller's words when it gives them.
std::string NoTrajectoriesNote(
    const std::function<std::string(const Advice&)>& explain_advice) {
  Advice give_paths;
  give_paths.settings = {{Option::kVerifyTrajectories, ""}};
  give_paths.stage = Stage::kReport;
  const std::string advice = explain_advice ? explain_advice(give_paths) : std::string();
  return fmt::format(
      "No trajectories were available: the result names no trajectory files and none "
      "were given{}.",
      advice.empty() ? "" : fmt::format(" ({})", advice));
}

}  // namespace

std::string VerificationSection(
    const VerificationSummary& v,
    const std::function<std::string(const Advice&)>& explain_advice) {
  std::string html =
      "<section id=\"verification\">\n<h2>Verification against GNSS</h2>\n";
  html += MetricsTable(v);
  if (v.corrected && v.corrected->start_end_distance_m > 0) {
    html += Paragraph(fmt::format(
        "Correction changed the start-to-end distance from {:.2f} m to {:.2f} m "
        "(the reference's own: {:.2f} m).",
        v.raw.start_end_distance_m,
        v.corrected->start_end_distance_m,
        v.reference.start_end_distance_m));
  }
  if (!v.warnings.empty()) html += WarningsList(v.warnings);
  if (!v.details.empty()) {
    Table t("meta");
    for (const auto& [what, value] : v.details) t.Row({what, value});
    html += fmt::format(
        "<details>\n<summary>How the paths were made</summary>\n{}</details>\n",
        t.Finish());
  }
  const std::string paths = PathFigure(v);
  if (paths.empty()) {
    html += Paragraph(NoTrajectoriesNote(explain_advice), "note");
  } else {
    html += paths;
    // A raw path that wandered off shrinks the reference to a dot: zoom.
    constexpr double kZoomRatio = 3.0;
    const double ref_extent = Extent(v.reference_path);
    if (v.corrected_path && ref_extent > 0 &&
        Extent(v.raw_path) > kZoomRatio * ref_extent) {
      html += PathFigure(v, false);
    }
    html += ErrorFigure(v);
  }
  return html + "</section>\n";
}

}  // namespace mpcal::report
