#include <string>
#include <string_view>

#include <fmt/format.h>

#include "report/html.h"
#include "report/sections.h"
#include "report/svg.h"

namespace mpcal::report {

std::string HeaderSection(const ReportInputs& inputs,
                          const std::string& generated_at,
                          const std::string& main_html) {
  std::string html = "<header>\n";
  html += fmt::format("<h1>{}</h1>\n", EscapeXml(inputs.title));
  Table t("meta");
  t.Row({"Generated", generated_at});
  t.Row({"Tool", std::string("mpcal ") + MPCAL_VERSION});
  for (const auto& [role, path] : inputs.input_files) t.Row({role, path});
  if (inputs.calibration && inputs.calibration->provenance) {
    const Provenance& p = *inputs.calibration->provenance;
    t.Row({"Calibration made by", "mpcal " + p.mpcal_version});
    if (!p.input.empty()) t.Row({"Calibration input", p.input});
    if (!p.options.empty()) t.Row({"Calibration options", p.options});
  }
  if (!inputs.command_line.empty()) t.Row({"Report command", inputs.command_line});
  html += t.Finish();

  // Links to the sections present (same page: no network), read from the
  // sections themselves, so that none can be left out.
  std::string nav;
  const std::string_view open = "<section id=\"";
  for (std::size_t at = main_html.find(open); at != std::string::npos;
       at = main_html.find(open, at + 1)) {
    const std::size_t id_begin = at + open.size();
    const std::size_t id_end = main_html.find('"', id_begin);
    const std::size_t title_begin = main_html.find("<h2>", id_end);
    const std::size_t title_end = main_html.find("</h2>", title_begin);
    if (id_end == std::string::npos || title_end == std::string::npos) break;
    // The h2 is already escaped HTML; copied as it is.
    nav += fmt::format(" <a href=\"#{}\">{}</a>",
                       main_html.substr(id_begin, id_end - id_begin),
                       main_html.substr(title_begin + 4, title_end - title_begin - 4));
  }
  if (!nav.empty()) html += fmt::format("<nav>Sections:{}</nav>\n", nav);
  return html + "</header>\n";
}

}  // namespace mpcal::report
