#include "report/split_half_table.h"

#include <cmath>

#include <fmt/format.h>

#include "mpcal/count.h"
#include "report/display_units.h"
#include "report/html.h"

namespace mpcal::report {

std::string SplitHalfTable(const SplitHalfSummary& check, ModelKind model) {
  const int p = ParameterCount(model);
  std::string html = "<h3>Split-half check</h3>\n";
  html += Paragraph(
      fmt::format("The used positions split in two (the first and second half by "
                  "time, and alternate positions), each half calibrated alone. z = "
                  "(first \u2212 second) / \u221a(\u03c3\u2081\u00b2 + "
                  "\u03c3\u2082\u00b2) is standard normal when the 1\u03c3 are "
                  "honest: RMS z about 1 \u00b1 {:.2f}; the halves disagree beyond "
                  "chance when the chi-square of the difference (with its "
                  "correlations) has p < {:g}.",
                  1.0 / std::sqrt(2.0 * p),
                  check.significance),
      "note");
  Table t;
  std::vector<std::string> header = {"Split", "Positions"};
  for (int i = 0; i < p; ++i) header.emplace_back(ParameterShortLabel(i));
  header.insert(header.end(), {"RMS z", "p", "Verdict"});
  t.Header(header);
  for (const SplitHalfComparison& c : check.comparisons) {
    std::vector<std::string> row = {
        c.kind == SplitKind::kByTime ? "by time" : "alternate positions",
        fmt::format("{} + {}", c.positions_first, c.positions_second)};
    for (int i = 0; i < p; ++i) {
      row.push_back(c.determined && i < static_cast<int>(c.z.size())
                        ? fmt::format("{:+.2f}", c.z[static_cast<std::size_t>(i)])
                        : "\u2014");
    }
    if (c.determined) {
      row.push_back(Fixed(c.rms_z, 2));
      row.push_back(Significant(c.p_value, 2));
      row.push_back(c.disagree ? "disagree" : "consistent");
    } else {
      row.insert(row.end(),
                 {"\u2014",
                  "\u2014",
                  fmt::format("not possible: a half needs {} more "
                              "than the parameters",
                              Count(SplitRedundancyNeeded(c.kind), "position"))});
    }
    t.Row(row, c.determined && c.disagree ? "bad" : "");
  }
  html += t.Finish();
  if (check.widening > 1.0) {
    html += Paragraph(
        fmt::format("Every 1\u03c3 above is widened by {:.2f}: \u221a(\u03c7\u00b2 "
                    "/ dof) of the split whose halves disagree.",
                    check.widening),
        "bad");
  }
  return html;
}

}  // namespace mpcal::report
