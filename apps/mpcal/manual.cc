// The man pages, written from the same CLI11 tables and with CLI11's own
// help formatter, so that a page says what `--help` says: the usage line,
// the options by group with their types and defaults, and the footer's
// examples.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <CLI/CLI.hpp>

#include "reference.h"

namespace mpcal::cli {
namespace {

// Decodes one UTF-8 sequence at text[i] (advancing i); an invalid byte is
// taken as itself.
std::uint32_t NextCodePoint(std::string_view text, std::size_t& i) {
  const auto lead = static_cast<unsigned char>(text[i]);
  const std::size_t extra = lead >= 0xF0 ? 3 : lead >= 0xE0 ? 2 : lead >= 0xC0 ? 1 : 0;
  if (extra == 0 || i + extra >= text.size()) {
    ++i;
    return lead;
  }
  std::uint32_t cp = lead & (0x3Fu >> extra);
  for (std::size_t k = 1; k <= extra; ++k) {
    cp = (cp << 6) | (static_cast<unsigned char>(text[i + k]) & 0x3Fu);
  }
  i += extra + 1;
  return cp;
}

// Text as roff reads it: backslashes and dashes escaped (`\-` is the
// hyphen-minus a reader can paste into a shell; a plain `-` may come out as
// a typographic hyphen), a leading dot or quote kept from being read as a
// request, and every non-ASCII character named (\[u03C3]) so that the page is
// ASCII and groff needs no input encoding.
std::string Roff(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    const bool line_start = i == 0 || text[i - 1] == '\n';
    if (static_cast<unsigned char>(c) >= 0x80) {
      out += fmt::format("\\[u{:04X}]", NextCodePoint(text, i));
      continue;
    }
    if (line_start && (c == '.' || c == '\'')) out += "\\&";
    if (c == '\\') {
      out += "\\e";
    } else if (c == '-') {
      out += "\\-";
    } else {
      out += c;
    }
    ++i;
  }
  return out;
}

std::string Join(const std::vector<std::string>& words, std::string_view separator) {
  return fmt::format("{}", fmt::join(words, separator));
}

/// "mpcal" and the subcommands down to `app`, joined by `separator`.
std::string Spelled(const CLI::App& app, std::string_view separator) {
  return fmt::format("mpcal{}{}",
                     app.get_parent() == nullptr ? "" : separator,
                     fmt::join(CommandPath(app), separator));
}

std::string PageName(const CLI::App& app) { return Spelled(app, "-"); }

std::string CommandLine(const CLI::App& app) { return Spelled(app, " "); }

std::string Upper(std::string text) {
  for (char& c : text) c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  return text;
}

// An option as --help shows it: the names in bold ("-o, --output"), then what
// CLI11 prints after them (type, default, REQUIRED, Needs, Excludes).
std::string OptionTag(const CLI::Formatter& formatter, const CLI::Option& option) {
  std::string tag;
  if (option.get_positional()) {
    tag = "\\fB" + Roff(option.get_name(true, false)) + "\\fR";
  } else {
    std::vector<std::string> names;
    for (const std::string& s : option.get_snames())
      names.push_back("\\fB\\-" + Roff(s) + "\\fR");
    for (const std::string& l : option.get_lnames()) {
      names.push_back("\\fB\\-\\-" + Roff(l) + "\\fR");
    }
    tag = Join(names, ", ");
  }
  const std::string opts = formatter.make_option_opts(&option);
  if (!opts.empty())
    tag += " \\fI" + Roff(opts.substr(opts.front() == ' ' ? 1 : 0)) + "\\fR";
  return tag;
}

void WriteOptions(std::ostringstream& out, const CLI::App& app) {
  const CLI::Formatter formatter;
  const std::vector<const CLI::Option*> options = ListedOptions(app);
  bool any_positional = false;
  for (const CLI::Option* o : options) {
    if (!o->get_positional()) continue;
    if (!any_positional) out << ".SH ARGUMENTS\n";
    any_positional = true;
    out << ".TP\n"
        << OptionTag(formatter, *o) << "\n"
        << Roff(o->get_description()) << "\n";
  }
  bool any_option = false;
  for (const std::string& group : app.get_groups()) {
    bool group_started = false;
    for (const CLI::Option* o : options) {
      if (o->get_positional() || o->get_group() != group) continue;
      if (!any_option) out << ".SH OPTIONS\n";
      any_option = true;
      if (!group_started) out << ".SS \"" << Roff(group) << "\"\n";
      group_started = true;
      out << ".TP\n"
          << OptionTag(formatter, *o) << "\n"
          << Roff(o->get_description()) << "\n";
    }
  }
}

// The footer: indented lines (the examples) are kept as they are; an
// "Example:" or "Examples:" line opens EXAMPLES; other lines are prose, in
// NOTES, one paragraph per run of lines.
void WriteFooter(std::ostringstream& out, const std::string& footer) {
  std::istringstream lines(footer);
  std::string line;
  std::string section;
  std::string paragraph;
  bool in_block = false;
  const auto flush_paragraph = [&] {
    if (paragraph.empty()) return;
    if (section != "NOTES") out << ".SH NOTES\n";
    section = "NOTES";
    out << ".PP\n" << Roff(paragraph) << "\n";
    paragraph.clear();
  };
  const auto end_block = [&] {
    if (in_block) out << ".fi\n.RE\n";
    in_block = false;
  };
  while (std::getline(lines, line)) {
    if (line == "Example:" || line == "Examples:") {
      flush_paragraph();
      end_block();
      out << ".SH EXAMPLES\n";
      section = "EXAMPLES";
    } else if (line.starts_with("  ")) {
      flush_paragraph();
      if (!in_block) out << ".RS 4\n.nf\n";
      in_block = true;
      out << Roff(line.substr(2)) << "\n";
    } else if (!line.empty()) {
      end_block();
      paragraph += (paragraph.empty() ? "" : " ") + line;
    }
  }
  flush_paragraph();
  end_block();
}

std::string Page(const CLI::App& app, const std::string& version_line) {
  std::ostringstream out;
  const std::string name = PageName(app);
  const std::string command = CommandLine(app);
  const std::string description = app.get_description();
  out << ".\\\" Written by `mpcal --generate man` from the flags `" << command
      << " --help` lists.\n";
  out << ".TH " << Roff(Upper(name)) << " 1 \"\" \"" << Roff(version_line)
      << "\" \"mpcal manual\"\n";
  // Flags and file names are not words: no hyphenation, no stretched spaces.
  out << ".nh\n.ad l\n";
  out << ".SH NAME\n" << Roff(name) << " \\- ";
  // The summary is the description up to its first line break (whatis(1)
  // and apropos(1) want one line), without the root's own "mpcal: ".
  std::string summary = description.substr(0, description.find('\n'));
  if (summary.starts_with(name + ": ")) summary.erase(0, name.size() + 2);
  out << Roff(summary) << "\n";

  const CLI::Formatter formatter;
  std::string usage = formatter.make_usage(&app, command);
  usage = usage.substr(usage.find(command) + command.size());
  usage = CLI::detail::trim_copy(usage);
  out << ".SH SYNOPSIS\n.B " << Roff(command) << "\n";
  if (!usage.empty()) out << Roff(usage) << "\n";
  out << ".SH DESCRIPTION\n" << Roff(description) << "\n";

  const std::vector<const CLI::App*> subcommands = Subcommands(app);
  if (!subcommands.empty()) {
    out << ".SH SUBCOMMANDS\n";
    for (const CLI::App* sub : subcommands) {
      out << ".TP\n.B " << Roff(sub->get_name()) << "\n"
          << Roff(sub->get_description()) << " (\\fB" << Roff(PageName(*sub))
          << "\\fR(1))\n";
    }
  }
  WriteOptions(out, app);
  WriteFooter(out, app.get_footer());
  if (app.get_parent() == nullptr) {
    out << ".SH \"EXIT STATUS\"\n"
           ".TP\n.B 0\nSuccess.\n"
           ".TP\n.B 1\nBad input or an input/output failure; the one line on standard "
           "error, \\(lqmpcal: error: \\&...\\(rq, says what, where and what to do.\n"
           ".TP\n.B 2\nA usage error: an unknown subcommand or flag, or a bad flag "
           "value.\n";
  }
  std::vector<std::string> related;
  if (const CLI::App* parent = app.get_parent()) related.push_back(PageName(*parent));
  for (const CLI::App* sub : subcommands) related.push_back(PageName(*sub));
  if (!related.empty()) {
    out << ".SH \"SEE ALSO\"\n";
    for (std::string& r : related) r = "\\fB" + Roff(r) + "\\fR(1)";
    out << Join(related, ",\n") << "\n";
  }
  return out.str();
}

void AddPages(const CLI::App& app,
              const std::string& version_line,
              std::vector<std::pair<std::string, std::string>>& pages) {
  pages.emplace_back(PageName(app) + ".1", Page(app, version_line));
  for (const CLI::App* sub : Subcommands(app)) AddPages(*sub, version_line, pages);
}

}  // namespace

std::vector<std::pair<std::string, std::string>> ManualPages(
    const CLI::App& root, const std::string& version_line) {
  std::vector<std::pair<std::string, std::string>> pages;
  AddPages(root, version_line, pages);
  return pages;
}

}  // namespace mpcal::cli
