#include "report/html.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "report/svg.h"

namespace mpcal::report {

namespace {

// The figures' strokes and fills are set here rather than per element, so
// that the print rules below can adjust them in one place. System fonts only:
// nothing is fetched.
constexpr std::string_view kCss = R"css(
:root { --ink: #1a1a1a; --muted: #555; --rule: #c8c8c8; --accent: #0072B2; }
* { box-sizing: border-box; }
body { margin: 0 auto; max-width: 1000px; padding: 1.2rem 1.5rem 3rem;
  font: 15px/1.45 system-ui, -apple-system, "Segoe UI", "DejaVu Sans", sans-serif;
  color: var(--ink); background: #fff; }
h1 { font-size: 1.6rem; margin: 0.2rem 0 0.6rem; }
h2 { font-size: 1.3rem; margin: 2rem 0 0.6rem; padding-bottom: 0.2rem;
  border-bottom: 2px solid var(--ink); }
h3 { font-size: 1.05rem; margin: 1.4rem 0 0.4rem; }
p { margin: 0.4rem 0; }
code, .mono { font-family: ui-monospace, "DejaVu Sans Mono", monospace; font-size: 0.9em;
  overflow-wrap: anywhere; }
table { border-collapse: collapse; margin: 0.5rem 0 1rem; font-variant-numeric: tabular-nums; }
th, td { padding: 0.25rem 0.6rem; border-bottom: 1px solid var(--rule); text-align: right;
  vertical-align: top; }
th { border-bottom: 1.5px solid var(--ink); font-weight: 600; }
th:first-child, td:first-child { text-align: left; }
table.trials td:first-child { white-space: nowrap; }
table.meta td, table.meta th { text-align: left; }
table.meta td:first-child { white-space: nowrap; }
table.meta td:last-child { overflow-wrap: anywhere; }
tr.bad td { font-weight: 600; }
tr.excluded td { color: var(--muted); font-style: italic; }
figure { margin: 0.8rem 0 1.4rem; break-inside: avoid; page-break-inside: avoid; }
figure svg { display: block; width: 100%; height: auto; max-width: 900px; }
figcaption { font-size: 0.9rem; color: var(--muted); margin-top: 0.3rem; }
.warnings { border-left: 4px solid #D55E00; padding: 0.3rem 0.8rem 0.3rem 2rem; margin: 0.6rem 0;
  background: #fdf3ec; }
.warnings li { margin: 0.15rem 0; }
.ok { border-left: 4px solid #009E73; padding: 0.3rem 0.8rem; background: #eef8f4; }
.note { color: var(--muted); font-size: 0.9rem; }
section { break-before: auto; }
details summary { cursor: pointer; color: var(--accent); }
svg text { font-family: system-ui, "DejaVu Sans", sans-serif; fill: #1a1a1a; }
svg .tick-label { font-size: 12px; }
svg .axis-label { font-size: 13px; font-weight: 600; }
svg .legend { font-size: 12px; }
svg .band-label, svg .point-label { font-size: 10px; fill: #333; }
svg .grid { stroke: #e3e3e3; stroke-width: 1; }
svg .tick { stroke: #1a1a1a; stroke-width: 1; }
svg .frame { fill: none; stroke: #1a1a1a; stroke-width: 1; }
svg .zero, svg .reference { stroke: #1a1a1a; stroke-width: 1; stroke-dasharray: 4 3; }
svg .band { fill: #9a9a9a; fill-opacity: 0.28; stroke: none; }
svg .band-excluded { fill: #D55E00; fill-opacity: 0.18; stroke: #D55E00;
  stroke-dasharray: 3 2; stroke-width: 0.8; }
svg .band-misfit { fill: #CC79A7; fill-opacity: 0.16; stroke: none; }
svg .stripe { fill: #f4f4f4; }
svg .bar { fill: #56B4E9; stroke: #1f4e79; stroke-width: 0.8; }
svg .bar-dark { fill: #1f4e79; stroke: #1a1a1a; stroke-width: 0.8; }
svg .bar-z { fill: #E69F00; stroke: #1a1a1a; stroke-width: 0.8; }
svg .bar-excluded { fill: #ffffff; stroke: #D55E00; stroke-width: 1.2; stroke-dasharray: 3 2; }
svg .disk { fill: #fbfbfb; stroke: #1a1a1a; stroke-width: 1.2; }
svg .guide { fill: none; stroke: #bdbdbd; stroke-width: 0.8; stroke-dasharray: 3 3; }
@media (max-width: 700px) { body { padding: 0.6rem; font-size: 14px; } }
@media print {
  body { max-width: none; padding: 0; font-size: 10.5pt; }
  h2 { break-after: avoid; page-break-after: avoid; }
  .warnings, .ok { background: none; }
  details { display: block; }
  details > summary { display: none; }
  a { color: inherit; text-decoration: none; }
  @page { margin: 15mm; }
}
)css";

}  // namespace

std::string PageBegin(std::string_view title) {
  return fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      "<meta name=\"generator\" content=\"mpcal\">\n"
      "<title>{}</title>\n<style>{}</style>\n</head>\n<body>\n",
      EscapeXml(title),
      kCss);
}

std::string PageEnd() { return "</body>\n</html>\n"; }

std::string Figure(const std::string& svg, std::string_view caption) {
  return fmt::format(
      "<figure>\n{}<figcaption>{}</figcaption>\n</figure>\n", svg, EscapeXml(caption));
}

Table::Table(std::string_view css_class) {
  html_ =
      css_class.empty() ? "<table>\n" : fmt::format("<table class=\"{}\">\n", css_class);
}

void Table::Header(const std::vector<std::string>& cells) {
  html_ += "<thead><tr>";
  for (const std::string& c : cells) html_ += fmt::format("<th>{}</th>", EscapeXml(c));
  html_ += "</tr></thead>\n";
}

void Table::Row(const std::vector<std::string>& cells, std::string_view row_class) {
  if (!body_open_) {
    html_ += "<tbody>\n";
    body_open_ = true;
  }
  html_ += row_class.empty() ? "<tr>" : fmt::format("<tr class=\"{}\">", row_class);
  for (const std::string& c : cells) html_ += fmt::format("<td>{}</td>", EscapeXml(c));
  html_ += "</tr>\n";
}

std::string Table::Finish() {
  std::string out = std::move(html_);
  if (body_open_) out += "</tbody>\n";
  out += "</table>\n";
  html_.clear();
  body_open_ = false;
  return out;
}

std::string Significant(double v, int significant) {
  if (!std::isfinite(v)) return "\u2014";
  if (v == 0.0) return "0";
  const int exponent = static_cast<int>(std::floor(std::log10(std::abs(v))));
  if (exponent < -4 || exponent >= 7) return fmt::format("{:.{}e}", v, significant - 1);
  const int decimals = std::max(0, significant - 1 - exponent);
  return fmt::format("{:.{}f}", v, decimals);
}

std::string Fixed(double v, int decimals) {
  if (!std::isfinite(v)) return "\u2014";
  return fmt::format("{:.{}f}", v, decimals);
}

std::string PlusMinus(double value, std::optional<double> sigma, int significant) {
  if (!std::isfinite(value)) return "\u2014";
  if (!sigma || !std::isfinite(*sigma) || *sigma <= 0.0) {
    return Significant(value, significant);
  }
  // Two significant digits of σ fix the decimal place of both numbers.
  const int exponent = static_cast<int>(std::floor(std::log10(*sigma)));
  const int decimals = std::clamp(1 - exponent, 0, 12);
  return fmt::format("{:.{}f} \u00b1 {:.{}f}", value, decimals, *sigma, decimals);
}

std::string Paragraph(std::string_view text, std::string_view css_class) {
  return css_class.empty()
             ? fmt::format("<p>{}</p>\n", EscapeXml(text))
             : fmt::format("<p class=\"{}\">{}</p>\n", css_class, EscapeXml(text));
}

std::string WarningsList(const std::vector<std::string>& warnings) {
  if (warnings.empty()) return Paragraph("No warnings.", "ok");
  std::string html = "<ul class=\"warnings\">\n";
  for (const std::string& w : warnings)
    html += fmt::format("<li>{}</li>\n", EscapeXml(w));
  return html + "</ul>\n";
}

}  // namespace mpcal::report
