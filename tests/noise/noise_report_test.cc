// The report's noise section, from a real `mpcal noise --json` file: the
// terms table and one log-log Allan plot per axis with its confidence band
// and the fitted terms.
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

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

}  // namespace
}  // namespace mpcal
