#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "mpcal/model.h"
#include "report/bar_chart.h"
#include "report/display_units.h"
#include "report/html.h"
#include "report/sections.h"
#include "report/sphere_map.h"
#include "report/split_half_table.h"
#include "report/svg.h"

namespace mpcal::report {

namespace {

std::string ParameterTable(const Calibration& c) {
  using Vec = Eigen::Matrix<double, kNumModelParameters, 1>;
  const Vec v = ToVector(c.model);
  const Vec s = c.std ? ToVector(*c.std) : Vec::Zero().eval();
  auto cell = [&](int i, double factor) {
    return PlusMinus(v[i] * factor,
                     c.std ? std::optional<double>(s[i] * factor) : std::nullopt);
  };
  Table t;
  t.Header({"Parameter", "Unit", "x", "y", "z"});
  t.Row({"Bias", "mg", cell(0, kMgPerMps2), cell(1, kMgPerMps2), cell(2, kMgPerMps2)});
  t.Row({"Bias", "m/s\u00b2", cell(0, 1), cell(1, 1), cell(2, 1)});
  if (c.input_units == AccelUnits::kCounts && c.mps2_per_unit > 0) {
    // Raw ADC: the bias holds the zero offset; in counts the user can check
    // it against the ADC's mid-scale.
    const double per_count = 1.0 / c.mps2_per_unit;
    t.Row({"Bias", "counts", cell(0, per_count), cell(1, per_count), cell(2, per_count)});
  }
  t.Row({"Scale-factor error", "ppm", cell(3, kPpm), cell(4, kPpm), cell(5, kPpm)});
  if (c.model_kind == ModelKind::kShinElSheimy9) {
    t.Row({"Non-orthogonality \u03b8yz, \u03b8zx, \u03b8zy",
           "mrad",
           cell(6, kMradPerRad),
           cell(7, kMradPerRad),
           cell(8, kMradPerRad)});
  } else {
    t.Row({"Non-orthogonality", "mrad", "held at 0", "held at 0", "held at 0"});
  }
  return t.Finish();
}

std::string ConditionsTable(const Calibration& c) {
  Table t("meta");
  t.Row({"Model", std::string(ToString(c.model_kind))});
  t.Row({"Gravity magnitude", Fixed(c.gravity_mps2, 5) + " m/s\u00b2"});
  std::string units(ToString(c.input_units));
  if (c.input_units == AccelUnits::kCounts) {
    units += fmt::format(" (nominal scale {:.6g} m/s\u00b2 per count)", c.mps2_per_unit);
  }
  t.Row({"Input units", units});
  return t.Finish();
}

std::string FitTable(const FitSummary& f) {
  auto mg_and_si = [](double mps2) {
    return fmt::format(
        "{} mg ({} m/s\u00b2)", Significant(mps2 * kMgPerMps2, 3), Significant(mps2, 3));
  };
  Table t("meta");
  t.Row({"Positions used", std::to_string(f.positions)});
  t.Row({"Positions excluded (outliers)", std::to_string(f.excluded_positions)});
  t.Row({"RMS of |a| \u2212 g before correction", mg_and_si(f.residual_rms_before_mps2)});
  t.Row({"RMS of |a| \u2212 g after correction", mg_and_si(f.residual_rms_after_mps2)});
  if (f.cross_validation_rms_mps2) {
    t.Row({"Cross-validation RMS (leave one position out)",
           mg_and_si(*f.cross_validation_rms_mps2)});
  }
  if (f.variance_factor) {
    t.Row(
        {"Variance factor \u03c3\u0302\u00b2 (\u2248 1 when noise explains the "
         "residuals)",
         Significant(*f.variance_factor, 3)});
  }
  t.Row({"Iterations", std::to_string(f.iterations)});
  t.Row({"Converged", f.converged ? "yes" : "NO"}, f.converged ? "" : "bad");
  return t.Finish();
}

std::string ResidualCharts(const Calibration& c) {
  std::vector<std::string> categories;
  BarSeries before{"|a| \u2212 g before correction", {}, "bar", {}};
  BarSeries after{"|a| \u2212 g after correction", {}, "bar-dark", {}};
  BarMarkers cv{"cross-validation: predicted by a fit without the position",
                {},
                {"#D55E00", "", MarkerShape::kDiamond, 1.6, false}};
  bool any_cv = false;
  bool any_excluded = false;
  for (std::size_t k = 0; k < c.positions.size(); ++k) {
    const PositionSummary& p = c.positions[k];
    categories.push_back(std::to_string(k + 1));
    before.values.push_back(p.residual_before_mps2 * kMgPerMps2);
    after.values.push_back(p.residual_after_mps2 * kMgPerMps2);
    const std::string cls = p.used ? "" : "bar-excluded";
    before.classes.push_back(cls);
    after.classes.push_back(cls);
    any_excluded |= !p.used;
    if (p.cross_validation_residual_mps2) {
      cv.values.emplace_back(*p.cross_validation_residual_mps2 * kMgPerMps2);
      any_cv = true;
    } else {
      cv.values.emplace_back(std::nullopt);
    }
  }
  std::vector<LegendEntry> excluded_legend;
  if (any_excluded) {
    excluded_legend.push_back({"excluded from the fit", {}, true, "bar-excluded", false});
  }
  // Two charts with their own scales: after correction the residuals are
  // often a hundred times smaller and would not show beside the raw ones.
  BarChartSpec b;
  b.aria_label = "Residual of each position before correction";
  b.axes = {"position (number, in recording order)", "|a| \u2212 g (mg)"};
  b.categories = categories;
  b.bars = {before};
  b.extra_legend = excluded_legend;
  BarChartSpec a = b;
  a.aria_label = "Residual of each position after correction";
  a.bars = {after};
  if (any_cv) a.markers = {cv};
  std::string html = Figure(
      BarChart(b),
      "Residual |a| \u2212 g of every static position with the raw readings (nominal "
      "scale only), in mg (1 mg = 0.00980665 m/s\u00b2).");
  html += Figure(BarChart(a),
                 any_cv ? "The same after correction, on its own scale; diamonds: the "
                          "residual predicted for the position by a fit made without "
                          "it (leave-one-out cross-validation). A position whose "
                          "diamond is far from its bar is not explained by the others."
                        : "The same after correction, on its own scale.");
  return html;
}

std::string CoverageFigure(const Calibration& c) {
  SphereMapSpec spec;
  spec.aria_label = "Orientations of the static positions on the sphere";
  for (std::size_t k = 0; k < c.positions.size(); ++k) {
    spec.points.push_back(
        {c.positions[k].mean_mps2, std::to_string(k + 1), c.positions[k].used});
  }
  spec.canonical = CanonicalCoverage(spec.points);
  int covered = 0;
  std::vector<std::string> missing;
  for (const CanonicalDirection& d : spec.canonical) {
    if (d.covered) {
      ++covered;
    } else {
      missing.push_back(d.name);
    }
  }
  std::string html = Figure(
      SphereMap(spec),
      fmt::format("Direction of the mean reading (the reaction to gravity, in the "
                  "sensor frame) at each position, numbered as above, on two "
                  "hemispheres in the azimuthal equal-area projection (equal areas of "
                  "the sphere look equal; the dashed circle is 45\u00b0 from the pole). "
                  "Squares and triangles: the 26 directions of a cube's faces, edges "
                  "and corners (Syed et al. 2007), covered when a used position lies "
                  "within {:.0f}\u00b0.",
                  kCoverageToleranceDeg));
  html += Paragraph(
      fmt::format("{} of the 26 canonical directions covered{}{}.",
                  covered,
                  missing.empty() ? "" : "; missing (named by what points down): ",
                  fmt::join(missing, ", ")),
      missing.empty() ? "ok" : "");
  return html;
}

std::string PositionsTable(const Calibration& c) {
  Table t;
  t.Header({"#",
            "start (s)",
            "end (s)",
            "samples",
            "direction of the reading",
            "before (mg)",
            "after (mg)",
            "cross-val. (mg)",
            "in fit"});
  for (std::size_t k = 0; k < c.positions.size(); ++k) {
    const PositionSummary& p = c.positions[k];
    const double norm = p.mean_mps2.norm();
    const Eigen::Vector3d u =
        norm > 0 ? Eigen::Vector3d(p.mean_mps2 / norm) : Eigen::Vector3d::Zero();
    t.Row({std::to_string(k + 1),
           Fixed(p.start_s, 2),
           Fixed(p.end_s, 2),
           std::to_string(p.samples),
           fmt::format("({:+.2f}, {:+.2f}, {:+.2f})", u.x(), u.y(), u.z()),
           Fixed(p.residual_before_mps2 * kMgPerMps2, 3),
           Fixed(p.residual_after_mps2 * kMgPerMps2, 3),
           p.cross_validation_residual_mps2
               ? Fixed(*p.cross_validation_residual_mps2 * kMgPerMps2, 3)
               : std::string("\u2014"),
           p.used ? "yes" : "excluded"},
          p.used ? "" : "excluded");
  }
  return fmt::format(
      "<details>\n<summary>Table of the {} positions</summary>\n{}</details>\n",
      c.positions.size(),
      t.Finish());
}

}  // namespace

std::string CalibrationSection(const Calibration& c) {
  std::string html = "<section id=\"calibration\">\n<h2>Calibration</h2>\n";
  html += ConditionsTable(c);
  html += "<h3>Parameters</h3>\n";
  html += Paragraph(
      c.std
          ? "Estimates \u00b1 1\u03c3 (covariance scaled by the variance factor). The "
            "corrected specific force is a = T \u00b7 diag(1/(1+s)) \u00b7 (Y \u2212 b)."
      : c.imported_from
          ? "No 1\u03c3: imported from " + *c.imported_from + ", which gives none."
          : std::string(
                "Values without uncertainty, no 1\u03c3 (a truth or hand-made file)."),
      "note");
  html += ParameterTable(c);
  if (c.fit) {
    html += "<h3>Fit</h3>\n";
    html += FitTable(*c.fit);
    if (c.fit->split_half) html += SplitHalfTable(*c.fit->split_half, c.model_kind);
  }
  html += "<h3>Warnings</h3>\n";
  html += WarningsList(c.warnings);
  if (!c.positions.empty()) {
    html += "<h3>Residual of every position</h3>\n";
    html += ResidualCharts(c);
    html += "<h3>Orientations covered</h3>\n";
    html += CoverageFigure(c);
    html += PositionsTable(c);
  }
  return html + "</section>\n";
}

}  // namespace mpcal::report
