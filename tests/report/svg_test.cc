// The plotting module: scales and ticks, number formats, escaping,
// decimation, the sphere's coverage, and the charts' SVG.
#include <cmath>
#include <regex>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "report/axes.h"
#include "report/bar_chart.h"
#include "report/html.h"
#include "report/line_plot.h"
#include "report/sphere_map.h"
#include "report/svg.h"
#include "report_fixtures.h"

namespace mpcal::report {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;
using ::testing::Not;

TEST(Svg, EscapesTheFiveMarkupCharacters) {
  EXPECT_EQ(EscapeXml("a<b>&\"c'"), "a&lt;b&gt;&amp;&quot;c&#39;");
  EXPECT_EQ(EscapeXml("plain µ ± text"), "plain µ ± text");
}

TEST(Svg, CoordinatesAreShortAndNeverNonFinite) {
  EXPECT_EQ(Coord(12.0), "12");
  EXPECT_EQ(Coord(12.345), "12.35");  // 12.345 is 12.3449999… in binary
  EXPECT_EQ(Coord(-0.001), "0");
  EXPECT_EQ(Coord(std::nan("")), "0");
}

TEST(Svg, StandardStylesDifferByDashAndMarkerNotOnlyColour) {
  for (int i = 0; i < 4; ++i) {
    for (int j = i + 1; j < 4; ++j) {
      EXPECT_TRUE(StandardStyle(i).dash != StandardStyle(j).dash ||
                  StandardStyle(i).marker != StandardStyle(j).marker)
          << i << " vs " << j;
      EXPECT_NE(StandardStyle(i).marker, StandardStyle(j).marker);
    }
  }
}

TEST(Axes, NiceTicksUseRoundStepsAndCoverTheRange) {
  Ticks t = NiceTicks({0.0, 9.3}, 5);
  EXPECT_DOUBLE_EQ(t.step, 2.0);
  EXPECT_THAT(t.values, ElementsAre(0, 2, 4, 6, 8, 10));
  t = NiceTicks({-0.0013, 0.0042}, 5);
  EXPECT_DOUBLE_EQ(t.step, 0.001);
  EXPECT_DOUBLE_EQ(t.range.lo, -0.002);
  EXPECT_DOUBLE_EQ(t.range.hi, 0.005);
  t = NiceTicks({1000.0, 1510.0}, 8);
  EXPECT_DOUBLE_EQ(t.step, 50.0);
}

TEST(Axes, TickLabelsHaveTheDecimalsTheStepNeeds) {
  EXPECT_EQ(FormatTick(0.30000000000000004, 0.1), "0.3");
  EXPECT_EQ(FormatTick(250.0, 50.0), "250");
  EXPECT_EQ(FormatTick(-0.0025, 0.0005), "-0.0025");
}

TEST(Axes, DataRangeIgnoresNonFiniteAndWidensAPoint) {
  const Interval r = DataRange({std::nan(""), 3.0, 1.0, INFINITY});
  EXPECT_EQ(r.lo, 1.0);
  EXPECT_EQ(r.hi, 3.0);
  const Interval p = DataRange({5.0});
  EXPECT_LT(p.lo, 5.0);
  EXPECT_GT(p.hi, 5.0);
  const Interval none = DataRange({});
  EXPECT_LT(none.lo, none.hi);
}

TEST(Html, PlusMinusRoundsToTwoDigitsOfSigma) {
  EXPECT_EQ(PlusMinus(12.6134, 0.0512), "12.613 \u00b1 0.051");
  EXPECT_EQ(PlusMinus(-1999.853, 12.4), "-2000 \u00b1 12");  // σ to 2 digits: units
  EXPECT_EQ(PlusMinus(0.00018, std::nullopt), "0.0001800");
  EXPECT_EQ(PlusMinus(1.5, 0.0), "1.500");
  EXPECT_EQ(Significant(1234567.0, 3), "1234567");
  EXPECT_EQ(Significant(2.5e-7, 2), "2.5e-07");
}

TEST(LinePlot, DecimationKeepsExtremesAndBoundsThePointCount) {
  std::vector<double> x(100000);
  std::vector<double> y(100000);
  for (std::size_t i = 0; i < x.size(); ++i) {
    x[i] = static_cast<double>(i);
    y[i] = std::sin(static_cast<double>(i) * 1e-3);
  }
  y[54321] = 50.0;   // a spike
  y[77777] = -40.0;  // and a dip
  std::vector<double> xo;
  std::vector<double> yo;
  DecimateMinMax(x, y, 2000, xo, yo);
  EXPECT_LE(xo.size(), 2000u);
  EXPECT_GE(xo.size(), 1900u);
  EXPECT_EQ(*std::max_element(yo.begin(), yo.end()), 50.0);
  EXPECT_EQ(*std::min_element(yo.begin(), yo.end()), -40.0);
  EXPECT_TRUE(std::is_sorted(xo.begin(), xo.end()));
  // Short input is returned unchanged.
  DecimateMinMax({1, 2, 3}, {4, 5, 6}, 2000, xo, yo);
  EXPECT_THAT(yo, ElementsAre(4, 5, 6));
}

TEST(LinePlot, EqualScaleGivesBothAxesTheSameStep) {
  LinePlotSpec spec;
  spec.equal_scale = true;
  spec.axes = {"east (m)", "north (m)"};
  spec.series.push_back({"path", {0, 40, 40, 0, 0}, {0, 0, 25, 25, 0}, StandardStyle(0)});
  const std::string svg = LinePlot(spec);
  // Tick labels of a 10 m step appear on both axes; a 5 m one on neither.
  EXPECT_THAT(svg, HasSubstr(">40</text>"));
  EXPECT_THAT(svg, HasSubstr(">20</text>"));
  EXPECT_THAT(svg, Not(HasSubstr(">25</text>")));
  EXPECT_THAT(svg, HasSubstr(">east (m)</text>"));
}

TEST(BarChart, DrawsOneBarPerFiniteValueAndMarkers) {
  BarChartSpec spec;
  spec.categories = {"1", "2", "3", "4"};
  spec.bars = {{"before", {1.0, -2.0, std::nan(""), 0.5}, "bar", {}}};
  spec.markers = {{"cv", {1.2, std::nullopt, std::nullopt, 0.4}, StandardStyle(3)}};
  const std::string svg = BarChart(spec);
  std::size_t bars = 0;
  for (std::size_t p = svg.find("class=\"bar\""); p != std::string::npos;
       p = svg.find("class=\"bar\"", p + 1)) {
    ++bars;
  }
  EXPECT_EQ(bars, 3u + 1u);  // three bars and the legend patch
  EXPECT_THAT(svg, Not(HasSubstr("nan")));
}

TEST(SphereMap, TheCubePositionsCoverAllTwentySixDirections) {
  std::vector<SpherePoint> points;
  for (const Eigen::Vector3d& u : mpcal::testing::CubeDirections()) {
    // Hand-held: 10° off, and scaled as readings in counts would be.
    const Eigen::Vector3d tilted =
        Eigen::AngleAxisd(10.0 * M_PI / 180, u.unitOrthogonal()) * u * 400.0;
    points.push_back({tilted, "", true});
  }
  std::vector<CanonicalDirection> c = CanonicalCoverage(points);
  ASSERT_EQ(c.size(), 26u);
  for (const CanonicalDirection& d : c) EXPECT_TRUE(d.covered) << d.name;
  // Named as detect names them, by what points down (the report
  // named the reading direction, detect the face down: opposite names).
  for (const CanonicalDirection& d : c) {
    if (d.direction.isApprox(Eigen::Vector3d::UnitZ())) {
      EXPECT_EQ(d.name, "-z face");
    }
    if (d.direction.isApprox(Eigen::Vector3d(1, 1, 1).normalized())) {
      EXPECT_EQ(d.name, "-x-y-z corner");
    }
  }
  // One point 21° from +z towards −y covers +z alone (the −y+z edge is 24°
  // away); at 23.5° it covers that edge instead.
  auto covered = [](const Eigen::Vector3d& u, bool used = true) {
    std::vector<std::string> names;
    for (const CanonicalDirection& d : CanonicalCoverage({{u, "", used}})) {
      if (d.covered) names.push_back(d.name);
    }
    return names;
  };
  const auto about_x = [](double deg) {
    return Eigen::AngleAxisd(deg * M_PI / 180, Eigen::Vector3d::UnitX()) *
           Eigen::Vector3d::UnitZ();
  };
  EXPECT_THAT(covered(about_x(21.0)), ElementsAre("-z face"));
  EXPECT_THAT(covered(about_x(23.5)), ElementsAre("+y-z edge"));  // 21.5° from the edge
  // 23° from +z at azimuth 22.5°: 25° from the +x+z edge, 34° from the
  // +x+y+z corner: covers nothing.
  const double tilt = 23.0 * M_PI / 180;
  const double azimuth = 22.5 * M_PI / 180;
  EXPECT_THAT(covered({std::sin(tilt) * std::cos(azimuth),
                       std::sin(tilt) * std::sin(azimuth),
                       std::cos(tilt)}),
              ElementsAre());
  EXPECT_THAT(covered(about_x(21.0), false), ElementsAre());  // excluded: never
}

// Two positions in one orientation (1 and 6 at the pole): each label clears
// the others instead of drawing over them ("16").
TEST(SphereMap, LabelsOfPositionsInOneOrientationDoNotOverlap) {
  SphereMapSpec spec;
  spec.points = {{Eigen::Vector3d::UnitZ(), "1", true},
                 {Eigen::Vector3d::UnitZ(), "6", true},
                 {Eigen::Vector3d::UnitZ(), "12", true}};
  const std::string svg = SphereMap(spec);
  const std::regex label(
      "<text x=\"([-0-9.]+)\" y=\"([-0-9.]+)\"[^>]*class=\"point-label\"");
  std::vector<std::pair<double, double>> at;
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), label);
       it != std::sregex_iterator();
       ++it) {
    at.emplace_back(std::stod((*it)[1]), std::stod((*it)[2]));
  }
  ASSERT_EQ(at.size(), 3u);
  for (std::size_t i = 0; i < at.size(); ++i) {
    for (std::size_t j = i + 1; j < at.size(); ++j) {
      const bool apart = std::abs(at[i].first - at[j].first) >= 12.0 ||
                         std::abs(at[i].second - at[j].second) >= 9.0;
      EXPECT_TRUE(apart) << "labels " << i << " and " << j << " overlap";
    }
  }
}

}  // namespace
}  // namespace mpcal::report
