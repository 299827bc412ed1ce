// The gyroscope section: M as scale-factor errors and
// misalignments ±1σ, the bias measured at every position against time, and,
// when the session's recording holds the gyroscope, every turn's residual
// before and after calibration and the turns' axes on the sphere.
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "mpcal/count.h"
#include "mpcal/error.h"
#include "mpcal/gyro.h"
#include "report/bar_chart.h"
#include "report/display_units.h"
#include "report/html.h"
#include "report/sections.h"
#include "report/sphere_map.h"

namespace mpcal::report {
namespace {

constexpr double kDegPerRad = 180.0 / std::numbers::pi;
constexpr const char* kAxisLetters = "xyz";

std::string MatrixTable(const GyroCalibration& g) {
  const bool has_std = g.m_covariance.has_value();
  const Eigen::Matrix3d s = g.MStd();
  auto cell = [&](int r, int c) {
    const double factor = r == c ? kPpm : kMradPerRad;
    const double value = r == c ? g.m(r, c) - 1.0 : g.m(r, c);
    return PlusMinus(value * factor,
                     has_std ? std::optional<double>(s(r, c) * factor) : std::nullopt);
  };
  Table t;
  t.Header({"Parameter", "Unit", "x", "y", "z"});
  t.Row({"Scale-factor error (M\u2093\u2093 \u2212 1, \u2026)",
         "ppm",
         cell(0, 0),
         cell(1, 1),
         cell(2, 2)});
  t.Row({"Misalignment, row x (m_xy, m_xz)", "mrad", "", cell(0, 1), cell(0, 2)});
  t.Row({"Misalignment, row y (m_yx, m_yz)", "mrad", cell(1, 0), "", cell(1, 2)});
  t.Row({"Misalignment, row z (m_zx, m_zy)", "mrad", cell(2, 0), cell(2, 1), ""});
  auto bias = [&](int i) {
    return PlusMinus(g.bias_radps[i] * kDegPerRad,
                     g.bias_std_radps
                         ? std::optional<double>((*g.bias_std_radps)[i] * kDegPerRad)
                         : std::nullopt);
  };
  t.Row({"Bias (mean over the positions)", "\u00b0/s", bias(0), bias(1), bias(2)});
  const Eigen::Vector3d change = g.BiasChangeRadps() * kDegPerRad;
  t.Row({"Bias change over the session (max \u2212 min)",
         "\u00b0/s",
         Significant(change[0], 3),
         Significant(change[1], 3),
         Significant(change[2], 3)});
  return t.Finish();
}

std::string FitParagraph(const GyroCalibration& g) {
  if (!g.fit) return "";
  const GyroFitSummary& f = *g.fit;
  return Paragraph(fmt::format(
      "{} between the static positions; {} after {} iterations. Gravity carried "
      "over each turn by the gyroscope against the direction measured after it: tilt "
      "RMS {:.3f}\u00b0 with the nominal scale and the bias measured at every position, "
      "{:.3f}\u00b0 calibrated. Variance factor {:.2f} (1: the turn residuals as the "
      "gyroscope's and accelerometer's noise explain them).",
      Count(f.turns, "turn"),
      f.converged ? "converged" : "did not converge",
      f.iterations,
      f.residual_rms_before_rad * kDegPerRad,
      f.residual_rms_after_rad * kDegPerRad,
      f.variance_factor));
}

std::string BiasFigure(const GyroCalibration& g) {
  if (g.position_bias.size() < 2) return "";
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const GyroBiasSample& b : g.position_bias) mean += b.bias_radps;
  mean /= static_cast<double>(g.position_bias.size());
  BarChartSpec spec;
  spec.aria_label = "Gyroscope bias at every static position";
  spec.axes = {"position (number, in recording order)",
               "bias \u2212 its mean (\u00b0/s)"};
  for (std::size_t k = 0; k < g.position_bias.size(); ++k) {
    spec.categories.push_back(std::to_string(k + 1));
  }
  for (int axis = 0; axis < 3; ++axis) {
    constexpr std::array<const char*, 3> kClass = {"bar", "bar-dark", "bar-z"};
    BarSeries series{fmt::format("{}", kAxisLetters[axis]), {}, kClass[axis], {}};
    for (const GyroBiasSample& b : g.position_bias) {
      series.values.push_back((b.bias_radps[axis] - mean[axis]) * kDegPerRad);
    }
    spec.bars.push_back(series);
  }
  return Figure(BarChart(spec),
                "Gyroscope bias measured at each static position (its mean reading "
                "at rest, Earth rate included) minus the mean over the positions, per "
                "axis: the drift over the session that the per-position bias keeps "
                "out of the scale factors.");
}

std::string TurnCharts(const std::vector<GyroTurn>& turns) {
  BarSeries before{"before (nominal scale)", {}, "bar", {}};
  BarSeries after{"after calibration", {}, "bar", {}};
  BarMarkers sigma{"1\u03c3 of the turn", {}, StandardStyle(2)};
  std::vector<std::string> categories;
  for (std::size_t k = 0; k < turns.size(); ++k) {
    categories.push_back(std::to_string(k + 1));
    before.values.push_back(turns[k].residual_before_rad * kDegPerRad);
    after.values.push_back(turns[k].residual_after_rad * kDegPerRad);
    sigma.values.emplace_back(turns[k].sigma_rad * kDegPerRad);
  }
  // Two charts with their own scales, as for the positions: the calibrated
  // residuals are often ten times smaller than the raw ones.
  BarChartSpec b;
  b.aria_label = "Tilt residual of each turn before calibration";
  b.axes = {"turn (number, in recording order)", "tilt (\u00b0)"};
  b.categories = categories;
  b.bars = {before};
  BarChartSpec a = b;
  a.aria_label = "Tilt residual of each turn after calibration";
  a.bars = {after};
  a.markers = {sigma};
  return Figure(BarChart(b),
                "Tilt between the gravity direction carried over each turn by the "
                "gyroscope (nominal scale, bias measured at every position) and the "
                "direction measured after the turn, in degrees.") +
         Figure(BarChart(a),
                "The same with the calibrated gyroscope, on its own scale; markers: "
                "the 1\u03c3 of each component of the turn's residual (gyroscope "
                "noise integrated over the turn and the two directions' noise).");
}

std::string AxesFigure(const std::vector<GyroTurn>& turns) {
  SphereMapSpec spec;
  spec.aria_label = "Axes of the turns on the sphere";
  for (std::size_t k = 0; k < turns.size(); ++k) {
    spec.points.push_back({turns[k].axis, std::to_string(k + 1), true});
  }
  return Figure(SphereMap(spec),
                "Axis of each turn (the calibrated rotation over it, in the body frame "
                "at its start), numbered as above, on two hemispheres in the azimuthal "
                "equal-area projection. The entries of M for an axis are determined "
                "only by turns about it: turns spread over the sphere determine all "
                "nine.");
}

}  // namespace

std::string GyroSection(const Calibration& calibration, const ReportSession* session) {
  if (!calibration.gyroscope) return "";
  const GyroCalibration& g = *calibration.gyroscope;
  std::string html = "<section id=\"gyroscope\">\n<h2>Gyroscope</h2>\n";
  html += Paragraph(
      "Model \u03c9 = M (raw \u00b7 scale \u2212 b): M a general 3\u00d73 matrix (scale "
      "factors on its diagonal, misalignments off it, in the accelerometer's frame), "
      "b the bias measured at every static position and interpolated across each "
      "turn; M estimated from the turns between the positions.");
  html += MatrixTable(g);
  html += FitParagraph(g);
  html += BiasFigure(g);
  if (session != nullptr &&
      session->recording.gyro_radps.size() == session->recording.size() &&
      !session->recording.empty()) {
    try {
      const std::vector<GyroTurn> turns = ScoreGyroTurns(
          session->recording, session->detection.intervals, calibration, g);
      if (!turns.empty()) html += TurnCharts(turns) + AxesFigure(turns);
    } catch (const Error& e) {
      html +=
          Paragraph(fmt::format("The turns could not be scored: {}", e.what()), "note");
    }
  }
  return html + "</section>\n";
}

}  // namespace mpcal::report
