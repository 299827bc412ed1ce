#include <string>

#include <fmt/format.h>

#include "report/html.h"
#include "report/sections.h"
#include "report/svg.h"

namespace mpcal::report {

std::string HeaderSection(const ReportInputs& inputs, const std::string& generated_at) {
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

  // Links to the sections present (same page: no network).
  std::string nav;
  auto link = [&nav](bool present, const char* id, const char* name) {
    if (present) nav += fmt::format(" <a href=\"#{}\">{}</a>", id, name);
  };
  link(inputs.calibration.has_value(), "calibration", "Calibration");
  link(inputs.session.has_value(), "session", "Session");
  link(inputs.repeatability.has_value(), "repeatability", "Repeatability");
  link(inputs.verification.has_value(), "verification", "Verification");
  if (!nav.empty()) html += fmt::format("<nav>Sections:{}</nav>\n", nav);
  return html + "</header>\n";
}

}  // namespace mpcal::report
