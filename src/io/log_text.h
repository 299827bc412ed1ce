// The log reader's small text helpers and the roles a column can play,
// shared by its parts (layout detection, the row parser, the chunk source,
// the row sink). Private to src/io.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "mpcal/advice.h"
#include "text/text.h"

namespace mpcal::logio {

/// What a column of a log holds.
enum Role : std::int8_t {
  kNone = 0,
  kTime,
  kAx,
  kAy,
  kAz,
  kGx,
  kGy,
  kGz,
};

/// The key of each role in a column mapping ("t=...,ax=...").
inline constexpr const char* kRoleKeys[] = {"", "t", "ax", "ay", "az", "gx", "gy", "gz"};

inline bool IsBlank(char c) { return c == ' ' || c == '\t'; }

// Trimming and case folding are the project's one text-helpers header's.
using text::Lower;
using text::Trim;

inline std::string_view StripQuotes(std::string_view s) {
  s = Trim(s);
  if (s.size() >= 2 && (s.front() == '"' || s.front() == '\'') && s.back() == s.front()) {
    s = s.substr(1, s.size() - 2);
  }
  return Trim(s);
}

/// At most `max` characters of `s`, control characters shown as '?'.
inline std::string Printable(std::string_view s, std::size_t max = 40) {
  std::string out;
  for (char c : s.substr(0, max)) {
    const auto u = static_cast<unsigned char>(c);
    out += (u < 0x20 || u == 0x7f) ? '?' : c;
  }
  if (s.size() > max) out += "...";
  return out;
}

/// "commas", "semicolons", "tabs" or "blanks".
inline std::string_view DelimiterName(char d) {
  switch (d) {
    case ',':
      return "commas";
    case ';':
      return "semicolons";
    case '\t':
      return "tabs";
    default:
      return "blanks";
  }
}

/// A line that holds no data: blank, or a `#` / `%` comment.
inline bool IsCommentOrBlank(std::string_view text) {
  std::size_t i = 0;
  while (i < text.size() && (IsBlank(text[i]) || text[i] == '\r' || text[i] == '\f')) {
    ++i;
  }
  return i == text.size() || text[i] == '#' || text[i] == '%';
}

/// Advice to set one of `settings` (alternatives).
inline Advice Give(std::vector<Setting> settings) {
  Advice advice;
  advice.settings = std::move(settings);
  return advice;
}

}  // namespace mpcal::logio
