// The HTML report as a whole: sections present exactly when their inputs
// are, well-formed markup, no external reference, escaping, the paper's units.
#include "mpcal/report.h"

#include <cmath>
#include <filesystem>
#include <limits>
#include <regex>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mpcal/calibration_file.h"
#include "mpcal/error.h"
#include "mpcal/noise_file.h"
#include "report_fixtures.h"
#include "test_util.h"

namespace mpcal {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

std::size_t Count(const std::string& haystack, const std::string& needle) {
  std::size_t n = 0;
  for (std::size_t p = haystack.find(needle); p != std::string::npos;
       p = haystack.find(needle, p + needle.size())) {
    ++n;
  }
  return n;
}

// Checks that every element is closed in order (void <meta> aside), that
// attribute values are quoted, and that every '&' starts an entity. Returns
// "" or the first problem.
std::string CheckMarkup(const std::string& html) {
  std::vector<std::string> stack;
  std::size_t p = 0;
  while ((p = html.find('<', p)) != std::string::npos) {
    if (html.compare(p, 9, "<!DOCTYPE") == 0) {
      p = html.find('>', p);
      continue;
    }
    const std::size_t end = html.find('>', p);
    if (end == std::string::npos) return "unterminated tag at " + std::to_string(p);
    const std::string tag = html.substr(p + 1, end - p - 1);
    if (Count(tag, "\"") % 2 != 0) return "unbalanced quotes in <" + tag + ">";
    if (tag.find('<') != std::string::npos) return "'<' inside a tag: <" + tag + ">";
    const bool closing = !tag.empty() && tag[0] == '/';
    const bool self_closing = !tag.empty() && tag.back() == '/';
    const std::string name =
        tag.substr(closing ? 1 : 0, tag.find_first_of(" />\n", 1) - (closing ? 1 : 0));
    if (closing) {
      if (stack.empty() || stack.back() != name) {
        return "</" + name + "> closes <" + (stack.empty() ? "nothing" : stack.back()) +
               ">";
      }
      stack.pop_back();
    } else if (!self_closing && name != "meta") {
      stack.push_back(name);
      if (name == "style") {  // CSS may hold '>' (child selectors); skip it whole
        p = html.find("</style>", end);
        continue;
      }
    }
    p = end + 1;
  }
  if (!stack.empty()) return "<" + stack.back() + "> never closed";
  static const std::regex kBareAmpersand("&(?![a-zA-Z]+;|#[0-9]+;)");
  if (std::regex_search(html, kBareAmpersand)) return "a bare '&'";
  return "";
}

std::string Section(const char* id) { return std::string("<section id=\"") + id + "\""; }

TEST(Report, SectionsArePresentExactlyWhenTheirInputIsGiven) {
  const ReportInputs full = testing::FullInputs();
  for (int mask = 0; mask < 16; ++mask) {
    ReportInputs in;
    if (mask & 1) in.calibration = full.calibration;
    if (mask & 2) in.session = full.session;
    if (mask & 4) in.repeatability = full.repeatability;
    if (mask & 8) in.verification = full.verification;
    const std::string html = RenderReport(in);
    SCOPED_TRACE("mask " + std::to_string(mask));
    EXPECT_EQ(Count(html, Section("calibration")), (mask & 1) ? 1u : 0u);
    EXPECT_EQ(Count(html, Section("session")), (mask & 2) ? 1u : 0u);
    EXPECT_EQ(Count(html, Section("repeatability")), (mask & 4) ? 1u : 0u);
    EXPECT_EQ(Count(html, Section("verification")), (mask & 8) ? 1u : 0u);
    // Figures: calibration 3 (residuals before, after, sphere), session 1,
    // repeatability 1 (with per-trial 1σ), verification 2 (paths, error).
    const std::size_t figures = ((mask & 1) ? 3 : 0) + ((mask & 2) ? 1 : 0) +
                                ((mask & 4) ? 1 : 0) + ((mask & 8) ? 2 : 0);
    EXPECT_EQ(Count(html, "<figure>"), figures);
    EXPECT_EQ(Count(html, "<svg "), figures);
    EXPECT_EQ(Count(html, "</svg>"), figures);
    EXPECT_EQ(CheckMarkup(html), "");
    if (mask == 0) {
      EXPECT_THAT(html, HasSubstr("Nothing to report"));
    }
  }
}

TEST(Report, IsWellFormedAndSelfContained) {
  const std::string html = RenderReport(testing::FullInputs());
  EXPECT_EQ(CheckMarkup(html), "");
  EXPECT_THAT(html, Not(HasSubstr("http://")));
  EXPECT_THAT(html, Not(HasSubstr("https://")));
  for (const char* tag : {"<script", "<img", "<link", "<iframe", "@import", "url("}) {
    EXPECT_THAT(html, Not(HasSubstr(tag))) << tag;
  }
  // Every href is an anchor on the page itself.
  const std::regex href("href=\"([^\"]*)\"");
  for (auto it = std::sregex_iterator(html.begin(), html.end(), href);
       it != std::sregex_iterator();
       ++it) {
    EXPECT_EQ((*it)[1].str().substr(0, 1), "#") << (*it)[1].str();
  }
  EXPECT_THAT(html, HasSubstr("@media print"));
  EXPECT_THAT(html, Not(HasSubstr("nan")));
  EXPECT_THAT(html, Not(HasSubstr("inf\"")));
}

TEST(Report, EscapesFileNamesAndMessages) {
  ReportInputs in = testing::FullInputs();
  in.input_files = {{"Calibration file", "a<b&\"c\".json"}};
  in.command_line = "mpcal report --calib 'x<y>.json'";
  in.session->recording.source = "<script>alert(1)</script>.csv";
  const std::string html = RenderReport(in);
  EXPECT_THAT(html, HasSubstr("a&lt;b&amp;&quot;c&quot;.json"));
  EXPECT_THAT(html, Not(HasSubstr("a<b&")));
  EXPECT_THAT(html, HasSubstr("&#39;x&lt;y&gt;.json&#39;"));
  EXPECT_THAT(html, HasSubstr("&lt;script&gt;alert(1)&lt;/script&gt;.csv"));
  EXPECT_THAT(html, Not(HasSubstr("<script>")));
  // The fixture's warning carries "<sigma>".
  EXPECT_THAT(html, HasSubstr("5 &lt;sigma&gt;"));
  EXPECT_EQ(CheckMarkup(html), "");
}

TEST(Report, ShowsParametersInThePapersUnits) {
  // Bias 12.61 mg ± 0.05 mg, scale 1250 ppm ± 2 ppm, θyz 0.18 mrad ± 0.01.
  const std::string html = RenderReport(testing::FullInputs());
  EXPECT_THAT(html, HasSubstr("<td>12.610 \u00b1 0.050</td>"));
  EXPECT_THAT(html, HasSubstr("<td>-13.920 \u00b1 0.050</td>"));
  EXPECT_THAT(html, HasSubstr("<td>0.12366 \u00b1 0.00049</td>"));  // m/s²
  EXPECT_THAT(html, HasSubstr("<td>1250.0 \u00b1 2.0</td>"));
  EXPECT_THAT(html, HasSubstr("<td>0.180 \u00b1 0.010</td>"));
  EXPECT_THAT(html, HasSubstr("<td>-1.670 \u00b1 0.010</td>"));
  // Axis titles carry units.
  EXPECT_THAT(html, HasSubstr("|a| \u2212 g (mg)"));
  EXPECT_THAT(html, HasSubstr("time since the first sample (s)"));
  EXPECT_THAT(html, HasSubstr("east (m)"));
  EXPECT_THAT(html, HasSubstr("north (m)"));
  EXPECT_THAT(html, HasSubstr("distance to reference (m)"));
}

TEST(Report, HeaderNamesVersionInputsAndOptions) {
  ReportInputs in = testing::FullInputs();
  in.command_line = "mpcal report --calib calib.json -o r.html";
  const std::string html = RenderReport(in);
  EXPECT_THAT(html, HasSubstr("2024-01-01 00:00:00 UTC"));
  EXPECT_THAT(html, HasSubstr(std::string("mpcal ") + MPCAL_VERSION_FOR_TEST));
  EXPECT_THAT(html, HasSubstr("<td>calib.json</td>"));
  EXPECT_THAT(html, HasSubstr("--model shin-el-sheimy-9"));  // provenance options
  EXPECT_THAT(html, HasSubstr("mpcal report --calib calib.json -o r.html"));
}

TEST(Report, DateDefaultsToNowInUtc) {
  ReportInputs in;
  const std::string html = RenderReport(in);
  EXPECT_TRUE(std::regex_search(html,
                                std::regex("<td>20[0-9]{2}-[01][0-9]-[0-3][0-9] "
                                           "[0-2][0-9]:[0-5][0-9]:[0-6][0-9] UTC</td>")));
}

TEST(Report, CoverageNamesTheMissingDirections) {
  // Only the six faces: 6 of 26 covered, the edges and corners missing.
  const std::vector<Eigen::Vector3d> cube = testing::CubeDirections();
  const std::vector<Eigen::Vector3d> faces(cube.begin(), cube.begin() + 6);
  ReportInputs in;
  in.calibration = testing::FixtureCalibration(faces);
  for (PositionSummary& p : in.calibration->positions) p.used = true;
  const std::string html = RenderReport(in);
  EXPECT_THAT(html,
              HasSubstr("6 of the 26 canonical directions covered; missing (named by "
                        "what points down): "));
  EXPECT_THAT(html, HasSubstr("+x+y+z corner"));
  EXPECT_THAT(html, HasSubstr("-x-y-z corner"));
  EXPECT_EQ(Count(html, "class=\"canonical missing\""), 20u + 4u)
      << "20 missing; the 4 edges on the equator are drawn in both hemispheres";
  const std::string all = RenderReport(testing::FullInputs());
  // Position 7 is excluded in the fixture: its direction is not covered.
  EXPECT_THAT(all, HasSubstr("25 of the 26 canonical directions covered"));
}

TEST(Report, ExcludedPositionsAreMarked) {
  const std::string html = RenderReport(testing::FullInputs());
  EXPECT_THAT(html, HasSubstr("class=\"bar-excluded\""));
  EXPECT_THAT(html, HasSubstr("position 7 (excluded)"));
  EXPECT_THAT(html, HasSubstr("class=\"band-excluded\""));
}

TEST(Report, CalibrationWithoutPositionsOrUncertaintyStillRenders) {
  ReportInputs in;
  Calibration c;  // a truth file: no std, no fit, no positions
  c.model = testing::FixtureModel();
  c.model_kind = ModelKind::kBiasScale6;
  in.calibration = c;
  const std::string html = RenderReport(in);
  EXPECT_THAT(html, HasSubstr(Section("calibration")));
  EXPECT_THAT(html, HasSubstr("held at 0"));
  EXPECT_THAT(html, HasSubstr("<td>12.61</td>"));
  EXPECT_EQ(Count(html, "<svg "), 0u);
  EXPECT_EQ(CheckMarkup(html), "");
}

TEST(Report, NonFiniteAndEmptyDataDoNotBreakTheFigures) {
  ReportInputs in = testing::FullInputs();
  in.session->recording.accel[10] = Eigen::Vector3d::Constant(std::nan(""));
  in.verification->raw_path->east_m[3] = std::numeric_limits<double>::infinity();
  std::string html = RenderReport(in);
  EXPECT_EQ(CheckMarkup(html), "");
  EXPECT_THAT(html, Not(HasSubstr("nan")));
  EXPECT_THAT(html, Not(HasSubstr("inf")));

  ReportInputs empty;
  empty.session = ReportSession{};
  html = RenderReport(empty);
  EXPECT_THAT(html, HasSubstr("The recording is empty."));
  EXPECT_EQ(CheckMarkup(html), "");
}

// Values no reader lets through (a bias of 1e308 read as inf mg) still print
// as a dash, never as "inf" or "nan".
TEST(Report, NonFiniteValuesPrintNoInfOrNanCell) {
  ReportInputs in = testing::FullInputs();
  in.repeatability->parameters[0].values[1] = 1e308;
  in.repeatability->parameters[0].mean = std::numeric_limits<double>::infinity();
  in.repeatability->parameters[4].std_sample = std::nan("");
  in.calibration->positions.at(0).residual_after_mps2 = 1e308;
  const std::string html = RenderReport(in);
  EXPECT_EQ(CheckMarkup(html), "");
  EXPECT_THAT(html, Not(HasSubstr("inf")));
  EXPECT_THAT(html, Not(HasSubstr("nan")));
}

// The links at the top name every section the report holds: the gyroscope
// and the noise too, each once, in the order of the page.
TEST(Report, LinksListEverySectionPresent) {
  ReportInputs in = testing::FullInputs();
  in.calibration = ReadCalibrationFile(mpcal::testing::TestDataPath("imu_trial_1.json"));
  in.noise = ReadNoiseFile(mpcal::testing::TestDataPath("noise_still.json"));
  const std::string html = RenderReport(in);
  ASSERT_EQ(CheckMarkup(html), "");
  const std::size_t nav_begin = html.find("<nav>");
  ASSERT_NE(nav_begin, std::string::npos);
  const std::string nav = html.substr(nav_begin, html.find("</nav>") - nav_begin);
  std::string expected = "<nav>Sections:";
  std::size_t sections = 0;
  static const std::regex kSection("<section id=\"([a-z]+)\">\n<h2>([^<]+)</h2>");
  for (auto it = std::sregex_iterator(html.begin(), html.end(), kSection);
       it != std::sregex_iterator();
       ++it, ++sections) {
    expected += " <a href=\"#" + (*it)[1].str() + "\">" + (*it)[2].str() + "</a>";
  }
  EXPECT_EQ(sections, 6u);  // calibration, gyroscope, session, repeatability,
                            // verification, noise
  EXPECT_EQ(nav, expected);
  EXPECT_THAT(nav, HasSubstr("<a href=\"#gyroscope\">Gyroscope</a>"));
  EXPECT_THAT(nav, HasSubstr("<a href=\"#noise\">Noise</a>"));
  // The product speaks of the product: no tracker numbers.
  EXPECT_THAT(html, Not(HasSubstr("issue")));
}

TEST(Report, ZoomsOnTheReferenceWhenTheRawPathWandersOff) {
  ReportInputs in;
  in.verification = testing::FixtureVerification(true);
  EXPECT_EQ(Count(RenderReport(in), "<svg "), 2u);  // raw within 3× the loop
  for (double& e : in.verification->raw_path->east_m) e *= 10.0;
  const std::string html = RenderReport(in);
  EXPECT_EQ(Count(html, "<svg "), 3u);
  EXPECT_THAT(html, HasSubstr("Zoom on the reference"));
  EXPECT_EQ(CheckMarkup(html), "");
}

TEST(Report, ShowsTheBiasOfARawCountsCalibrationInCounts) {
  ReportInputs in;
  Calibration c;
  c.input_units = AccelUnits::kCounts;
  c.mps2_per_unit = 0.0025;  // 400 counts per m/s²
  c.model.bias_mps2 = Eigen::Vector3d(81.92, 82.0, 81.0);
  in.calibration = c;
  const std::string html = RenderReport(in);
  EXPECT_THAT(html,
              HasSubstr("<td>counts</td><td>32768</td><td>32800</td><td>32400</td>"));
  EXPECT_THAT(html, HasSubstr("0.0025 m/s\u00b2 per count"));
}

TEST(Report, VerificationWithoutPathsSaysHowToGiveThem) {
  ReportInputs in;
  in.verification = testing::FixtureVerification(false);
  // The advice in the caller's words (the mpcal command's: its flag).
  in.explain_advice = [](const Advice& advice) {
    return advice.settings.size() == 1 &&
                   advice.settings[0].option == Option::kVerifyTrajectories &&
                   advice.stage == Stage::kReport
               ? std::string("mpcal report --verify-trajectories PREFIX")
               : std::string("?");
  };
  const std::string html = RenderReport(in);
  EXPECT_THAT(html, HasSubstr("<td>15.30</td>"));
  EXPECT_THAT(html, HasSubstr("<td>1.60</td>"));
  EXPECT_THAT(html, HasSubstr("--verify-trajectories"));
  EXPECT_EQ(Count(html, "<svg "), 0u);
  // Without a caller's words, the page states the fact only.
  in.explain_advice = nullptr;
  EXPECT_THAT(RenderReport(in),
              HasSubstr("the result names no trajectory files and none were given."));
}

TEST(Report, RepeatabilityWithoutTrialSigmaPlotsEachUnitApart) {
  ReportInputs in;
  in.repeatability = testing::FixtureRepeatability(false);
  const std::string html = RenderReport(in);
  // Bias in mg, scale in ppm, angles in mrad: three plots.
  EXPECT_EQ(Count(html, "<svg "), 3u);
  EXPECT_THAT(html, HasSubstr("deviation from the mean across trials (mg)"));
  EXPECT_THAT(html, HasSubstr("no uncertainty given"));
  in.repeatability = testing::FixtureRepeatability(true);
  const std::string with_sigma = RenderReport(in);
  EXPECT_EQ(Count(with_sigma, "<svg "), 1u);
  EXPECT_THAT(with_sigma,
              HasSubstr("Changed between sessions beyond their uncertainty: "
                        "bias x, bias y, bias z."));
  // Trial 1 of bias x is 12.61 − 8 mg = 4.61 mg.
  // Rows line up to two digits of their finest uncertainty (0.050 mg).
  EXPECT_THAT(with_sigma, HasSubstr("<td>4.610</td>"));
  // Bias trials lie 160σ and 128σ from the mean: clipped to ±10σ, written out.
  EXPECT_THAT(with_sigma, HasSubstr("-160 \u2190"));
  EXPECT_THAT(with_sigma, HasSubstr("\u2192 32, 128"));
}

TEST(Report, WriteReportIsAtomic) {
  testing::ScratchDir dir;
  const std::string path = dir.Path("r.html");
  WriteReport(path, testing::FullInputs());
  EXPECT_EQ(testing::ReadFile(path), RenderReport(testing::FullInputs()));
  EXPECT_THROW(WriteReport(dir.Path("missing/r.html"), testing::FullInputs()), Error);
  EXPECT_FALSE(std::filesystem::exists(dir.Path("missing")));
}

}  // namespace
}  // namespace mpcal
