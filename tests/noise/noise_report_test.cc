// The report's noise section, from a real `mpcal noise --json` file: the
// terms table and one log-log Allan plot per axis with its confidence band
// and the fitted terms.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "mpcal/noise_file.h"
#include "mpcal/report.h"
#include "test_util.h"

namespace mpcal {
namespace {

using ::testing::HasSubstr;

std::size_t Count(const std::string& s, const std::string& what) {
  std::size_t n = 0;
  for (std::size_t p = s.find(what); p != std::string::npos; p = s.find(what, p + 1)) ++n;
  return n;
}

TEST(NoiseReport, SectionHasTheTableAndALogLogPlotPerAxis) {
  ReportInputs in;
  in.noise = ReadNoiseFile(std::string(MPCAL_TEST_DATA_DIR) + "/noise_still.json");
  in.generated_at = "2026-01-01 00:00:00 UTC";
  const std::string html = RenderReport(in);
  const std::size_t begin = html.find("<section id=\"noise\">");
  ASSERT_NE(begin, std::string::npos);
  const std::string section = html.substr(begin, html.find("</section>", begin) - begin);
  EXPECT_EQ(Count(section, "<svg"), 6u);        // 3 axes × accelerometer and gyroscope
  EXPECT_EQ(Count(section, "<polygon"), 6u);    // a confidence band in each
  EXPECT_THAT(section, HasSubstr("10\u207b"));  // decade ticks: 10⁻ⁿ
  EXPECT_THAT(section, HasSubstr("white noise N"));
  EXPECT_THAT(section, HasSubstr("sum of the fitted terms"));
  EXPECT_THAT(section, HasSubstr("not measured: &lt; "));  // the random walk of 3 minutes
  // How long to record: the sensor's one figure, as the command prints it.
  EXPECT_THAT(section, HasSubstr("record \u2265 5 min"));
  EXPECT_THAT(section, HasSubstr("\u00b5g/\u221aHz"));
  EXPECT_THAT(section, ::testing::Not(HasSubstr("nan")));
  EXPECT_THAT(section, ::testing::Not(HasSubstr("inf\"")));
}

std::string NoiseSectionOf(const NoiseFile& noise) {
  ReportInputs in;
  in.noise = noise;
  in.generated_at = "2026-01-01 00:00:00 UTC";
  const std::string html = RenderReport(in);
  const std::size_t begin = html.find("<section id=\"noise\">");
  EXPECT_NE(begin, std::string::npos);
  return html.substr(begin, html.find("</section>", begin) - begin);
}

// The points of the polyline of the series whose title begins with `title`
// (the n-th such series); -1 when there is none.
int PolylinePoints(const std::string& svg, const std::string& title, int nth) {
  std::size_t at = 0;
  for (int k = 0; k <= nth; ++k) {
    at = svg.find("<title>" + title, at);
    if (at == std::string::npos) return -1;
    ++at;
  }
  const std::size_t points = svg.find("points=\"", at);
  const std::size_t end = svg.find('"', points + 8);
  const std::string list = svg.substr(points + 8, end - points - 8);
  return static_cast<int>(Count(list, ","));
}

// Each measured term is drawn over the cluster times it was read from: its
// line has one point per cluster time of its τ range (the JSON's
// tau_range_s, read here without mpcal's reader), its title names the range.
TEST(NoiseReport, EachTermsLineSpansTheRangeItWasReadFrom) {
  const std::string path = std::string(MPCAL_TEST_DATA_DIR) + "/noise_still.json";
  std::ifstream in(path);
  const nlohmann::json doc = nlohmann::json::parse(in);
  const std::string section = NoiseSectionOf(ReadNoiseFile(path));
  int checked = 0;
  int nth_white = 0;
  for (const char* sensor : {"accelerometer", "gyroscope"}) {
    const bool gyro = std::string(sensor) == "gyroscope";
    for (const char* axis : {"x", "y", "z"}) {
      const nlohmann::json& a = doc[sensor]["axes"][axis];
      const std::vector<double> tau = a["allan"]["tau_s"].get<std::vector<double>>();
      for (const auto& [key, title] :
           {std::pair{gyro ? "white_noise_radps_per_rthz" : "white_noise_mps2_per_rthz",
                      "white noise N"},
            std::pair{gyro ? "bias_instability_radps" : "bias_instability_mps2",
                      "bias instability B"}}) {
        const nlohmann::json& t = a[key];
        if (t["status"] != "measured") continue;
        const double lo = t["tau_range_s"][0], hi = t["tau_range_s"][1];
        int inside = 0;
        for (double x : tau) inside += x >= lo && x <= hi;
        ASSERT_GE(inside, 2) << sensor << " " << axis << " " << key;
        const bool white = std::string(title) == "white noise N";
        // The white noise of every axis comes in the order drawn; the bias
        // instability only on the accelerometer's x axis (the first).
        const int points = PolylinePoints(section, title, white ? nth_white++ : 0);
        EXPECT_EQ(points, inside) << sensor << " " << axis << " " << key;
        ++checked;
      }
    }
  }
  EXPECT_EQ(checked, 7);  // N on the six axes, B on the accelerometer's x
  // The ranges in the titles: N of the accelerometer's x from 0.04 to 12 s,
  // B from 14 to 41 s.
  EXPECT_THAT(section, HasSubstr("read over \u03c4 0.04\u201312 s"));
  EXPECT_THAT(section, HasSubstr("read over \u03c4 14\u201341 s"));
}

// Where the model check found the model outside the curve's interval, the
// plot shades those cluster times (one band per range) and says so.
TEST(NoiseReport, MisfitRangesAreShaded) {
  NoiseFile noise = ReadNoiseFile(std::string(MPCAL_TEST_DATA_DIR) + "/noise_still.json");
  EXPECT_EQ(Count(NoiseSectionOf(noise), "band-misfit"), 0u);
  ModelCheck& c = noise.result.accel_mps2.axes[1].check;
  c.fits = false;
  c.disagree = {TauRange{0.5, 2.0}, TauRange{10.0, 20.0}};
  const std::string section = NoiseSectionOf(noise);
  EXPECT_EQ(Count(section, "class=\"band-misfit\""), 2u + 1u);  // two, the legend's
  EXPECT_THAT(section, HasSubstr("the model misses the curve"));
  // The bands on the log τ axis: 0.5–2 s is two octaves wide, 10–20 s one,
  // and the second begins log2(20) octaves after the first.
  std::vector<double> x, w;
  for (std::size_t at = section.find("<rect x=\""); at != std::string::npos;
       at = section.find("<rect x=\"", at + 1)) {
    const std::size_t end = section.find("/>", at);
    const std::string rect = section.substr(at, end - at);
    if (rect.find("band-misfit") == std::string::npos) continue;
    double rx = 0, ry = 0, rw = 0;
    ASSERT_EQ(std::sscanf(
                  rect.c_str(), "<rect x=\"%lf\" y=\"%lf\" width=\"%lf\"", &rx, &ry, &rw),
              3);
    x.push_back(rx);
    w.push_back(rw);
  }
  ASSERT_GE(x.size(), 2u);
  EXPECT_NEAR(w[0] / w[1], 2.0, 0.02);
  EXPECT_NEAR((x[1] - x[0]) / w[1], std::log2(20.0), 0.03);
}

}  // namespace
}  // namespace mpcal
