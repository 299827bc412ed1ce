// Small text helpers for every room that reads text (logs, GNSS references,
// trajectory CSVs): case folding, trimming, splitting into fields and lines.
// Header-only and standard-library-only, so that any room, model included,
// may use it without a link dependency (the rooms all see src/ privately).
// Reading a whole file is ReadTextInput (mpcal/text_input.h, in io).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace mpcal::text {

/// ASCII space, tab, CR, LF, vertical tab or form feed (locale-independent).
constexpr bool IsSpace(char c) {
  return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\v' || c == '\f';
}

/// `s` in ASCII lower case (locale-independent; other bytes unchanged).
inline std::string Lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return out;
}

/// `s` without leading and trailing white space (IsSpace).
constexpr std::string_view Trim(std::string_view s) {
  while (!s.empty() && IsSpace(s.front())) s.remove_prefix(1);
  while (!s.empty() && IsSpace(s.back())) s.remove_suffix(1);
  return s;
}

/// The fields of `line` between `delimiter`s, each trimmed; "" gives one
/// empty field, "a," gives "a" and "".
inline std::vector<std::string_view> SplitOn(std::string_view line, char delimiter) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t pos = line.find(delimiter, start);
    if (pos == std::string_view::npos) {
      fields.push_back(Trim(line.substr(start)));
      return fields;
    }
    fields.push_back(Trim(line.substr(start, pos - start)));
    start = pos + 1;
  }
}

/// The runs of non-space characters of `line`.
inline std::vector<std::string_view> SplitWhitespace(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && IsSpace(line[i])) ++i;
    const std::size_t start = i;
    while (i < line.size() && !IsSpace(line[i])) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

/// `text` cut into lines at LF (a CR before it dropped), so that line k
/// (1-based) is element k-1. No element for the end after a final LF.
inline std::vector<std::string_view> Lines(std::string_view text) {
  std::vector<std::string_view> lines;
  while (!text.empty()) {
    const std::size_t pos = text.find('\n');
    std::string_view line = text.substr(0, pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back(line);
    if (pos == std::string_view::npos) break;
    text.remove_prefix(pos + 1);
  }
  return lines;
}

}  // namespace mpcal::text
