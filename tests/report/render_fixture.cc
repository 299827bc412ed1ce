// Writes reports from the test fixtures for the browser test
// (render_test.sh): `mpcal_report_render_fixture full OUT.html` has every
// section; `minimal` only the calibration, with no positions.
#include <cstdio>
#include <exception>
#include <string>

#include "mpcal/report.h"
#include "report_fixtures.h"

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s full|minimal OUT.html\n", argv[0]);
    return 2;
  }
  try {
    const std::string kind = argv[1];
    mpcal::ReportInputs in;
    if (kind == "full") {
      in = mpcal::testing::FullInputs();
    } else if (kind == "minimal") {
      mpcal::Calibration c;
      c.model = mpcal::testing::FixtureModel();
      in.calibration = c;
      in.generated_at = "2024-01-01 00:00:00 UTC";
    } else {
      std::fprintf(stderr, "unknown kind %s\n", kind.c_str());
      return 2;
    }
    mpcal::WriteReport(argv[2], in);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 0;
}
