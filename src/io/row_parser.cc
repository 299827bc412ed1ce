#include "row_parser.h"

#include <cmath>
#include <cstring>
#include <system_error>
#include <utility>

#include <fmt/format.h>

#include "mpcal/plausible.h"

namespace mpcal::logio {
namespace {

bool IsLineEnd(char c) { return c == '\n' || c == '\r'; }

}  // namespace

RowParser::RowParser(const LogLayout& layout, std::vector<Role> roles, AccelUnits units)
    : layout_(layout),
      roles_(std::move(roles)),
      units_(units),
      max_reading_(MaxReading(units)),
      number_format_{fast_float::chars_format::general, layout.decimal_point} {}

// One field from `p` (just past its delimiter) to `stop`: returns where it
// ends (at the next delimiter, a blank, or the end), or nullptr with `why`.
// Spreadsheets and some loggers quote every field ("0.981"); a '+' before
// the number and blanks around it are allowed.
template <bool kInChunk>
const char* RowParser::ParseField(const char* p,
                                  const char* stop,
                                  int column,
                                  double* value,
                                  const char** number_begin,
                                  const char** number_end,
                                  RowFailure* why) const {
  const char delimiter = layout_.delimiter;
  const bool blanks = delimiter == ' ';
  if (!blanks) {
    while (p < stop && IsBlank(*p)) ++p;
  }
  const char* const field_begin = p;
  auto bad = [&]() -> const char* {
    *why = {RowFailure::Kind::kBadNumber, column, field_begin, nullptr};
    return nullptr;
  };
  const char quote = p < stop && (*p == '"' || *p == '\'') ? *p : '\0';
  if (quote != '\0') ++p;
  *number_begin = p;
  if (p < stop && *p == '+') ++p;
  const auto result = fast_float::from_chars_advanced(p, stop, *value, number_format_);
  const char* const after = result.ptr;
  const char* field_end = after;
  if (quote != '\0') {
    if (after == stop || *after != quote) return bad();
    ++field_end;
  }
  const bool at_end = field_end == stop || IsBlank(*field_end) ||
                      (!blanks && *field_end == delimiter) ||
                      (kInChunk && IsLineEnd(*field_end));
  if (result.ec != std::errc() || !at_end || (p != *number_begin && *p == '-')) {
    return bad();
  }
  *number_end = after;
  if (!std::isfinite(*value)) {
    *why = {RowFailure::Kind::kNonFinite, column, *number_begin, after};
    return nullptr;
  }
  // One row of 1e308 would poison detection's threshold (or 1e20 its
  // statistics): a reading no accelerometer can give is refused here.
  const Role role = roles_[column];
  if (role >= kAx && role <= kAz && std::abs(*value) > max_reading_) {
    *why = {RowFailure::Kind::kImpossible, column, *number_begin, after};
    return nullptr;
  }
  if (!blanks) {
    while (field_end < stop && IsBlank(*field_end)) ++field_end;
    if (field_end != stop && *field_end != delimiter &&
        !(kInChunk && IsLineEnd(*field_end)))
      return bad();
  }
  return field_end;
}

const char* RowParser::ParseInChunk(const char* p,
                                    const char* end,
                                    double* by_role) const {
  const char delimiter = layout_.delimiter;
  const bool blanks = delimiter == ' ';
  const int columns = static_cast<int>(roles_.size());
  RowFailure why;
  for (int column = 0; column < columns; ++column) {
    if (blanks) {
      while (p < end && IsBlank(*p)) ++p;
      if (p == end || IsLineEnd(*p)) return nullptr;
    } else if (column > 0) {
      if (p == end || *p != delimiter) return nullptr;
      ++p;
    }
    const Role role = roles_[column];
    if (role == kNone) {  // not needed: skipped, not converted
      while (p < end && *p != '\n' && (blanks ? !IsBlank(*p) : *p != delimiter)) ++p;
      continue;
    }
    const char* number_begin = nullptr;
    const char* number_end = nullptr;
    p = ParseField<true>(
        p, end, column, &by_role[role], &number_begin, &number_end, &why);
    if (p == nullptr) return nullptr;
  }
  // The last field ended at the line's end, or at what starts the columns
  // nobody reads (extra columns, trailing blanks).
  if (p == end) return end;
  if (*p == '\n') return p + 1;
  if (*p == '\r') {
    if (p + 1 == end) return end;
    return p[1] == '\n' ? p + 2 : nullptr;
  }
  const auto* nl = static_cast<const char*>(std::memchr(p, '\n', end - p));
  return nl != nullptr ? nl + 1 : end;
}

bool RowParser::Parse(std::string_view text, LogLine* out, RowFailure* why) const {
  const char* const line_begin = text.data();
  const char* p = line_begin;
  const char* const stop = line_begin + text.size();
  const char delimiter = layout_.delimiter;
  const bool blanks = delimiter == ' ';
  const int columns = static_cast<int>(roles_.size());
  auto span = [line_begin](const char* begin, const char* end) {
    return std::pair{static_cast<std::uint32_t>(begin - line_begin),
                     static_cast<std::uint32_t>(end - line_begin)};
  };
  for (int column = 0; column < columns; ++column) {
    // The field's start: past blanks, or past the delimiter that ended the
    // previous field.
    if (blanks) {
      while (p < stop && IsBlank(*p)) ++p;
    }
    if ((blanks || column > 0) && p == stop) {
      *why = {RowFailure::Kind::kTooFew, column, p, nullptr};
      return false;
    }
    if (!blanks && column > 0) ++p;
    const Role role = roles_[column];
    if (role == kNone) {  // not needed: skipped, not converted
      if (blanks) {
        while (p < stop && !IsBlank(*p)) ++p;
      } else {
        const auto* d = static_cast<const char*>(std::memchr(p, delimiter, stop - p));
        p = d != nullptr ? d : stop;
      }
      continue;
    }
    double value = 0.0;
    const char* number_begin = nullptr;
    const char* number_end = nullptr;
    p = ParseField<false>(p, stop, column, &value, &number_begin, &number_end, why);
    if (p == nullptr) return false;
    if (role == kTime) {
      out->time_raw = value;
    } else if (role <= kAz) {
      out->accel[role - kAx] = value;
      out->accel_span[role - kAx] = span(number_begin, number_end);
    } else {
      out->gyro[role - kGx] = value;
      out->gyro_span[role - kGx] = span(number_begin, number_end);
    }
  }
  return true;
}

std::string RowParser::ColumnLabel(int column) const {
  const bool named =
      column < static_cast<int>(layout_.column_names.size()) && layout_.header_line > 0;
  const Role role = column < static_cast<int>(roles_.size()) ? roles_[column] : kNone;
  const std::string name = named ? layout_.column_names[column] : kRoleKeys[role];
  return fmt::format("column '{}' (index {})", name, column);
}

std::string RowParser::TooFew(std::string_view text, int found) const {
  return fmt::format("expected at least {} columns separated by {} ({}), found {}: '{}'",
                     layout_.min_columns,
                     DelimiterName(layout_.delimiter),
                     layout_.Describe(),
                     found,
                     Printable(text, 80));
}

std::string RowParser::BadNumber(std::string_view text,
                                 int column,
                                 const char* field_begin) const {
  const char* const stop = text.data() + text.size();
  const char* e = field_begin;
  while (e < stop &&
         !(layout_.delimiter == ' ' ? IsBlank(*e) : *e == layout_.delimiter)) {
    ++e;
  }
  const std::string_view field = Trim(std::string_view(field_begin, e - field_begin));
  if (field.empty())
    return fmt::format("{} is empty; expected a number", ColumnLabel(column));
  return fmt::format(
      "expected a number in {}, found '{}'", ColumnLabel(column), Printable(field));
}

std::string RowParser::Problem(std::string_view text, const RowFailure& why) const {
  auto number = [&why] { return std::string_view(why.at, why.end - why.at); };
  switch (why.kind) {
    case RowFailure::Kind::kTooFew:
      return TooFew(text, why.column);
    case RowFailure::Kind::kBadNumber:
      return BadNumber(text, why.column, why.at);
    case RowFailure::Kind::kNonFinite:
      return fmt::format("non-finite value '{}' in {}; remove or fix the line",
                         number(),
                         ColumnLabel(why.column));
    case RowFailure::Kind::kImpossible:
      return fmt::format(
          "reading '{}' in {} is beyond any accelerometer's range (±{:g} {}, {:g} g): a "
          "corrupt line, or readings in other units",
          number(),
          ColumnLabel(why.column),
          max_reading_,
          ToString(units_),
          kMaxReadingG);
  }
  return "";
}

}  // namespace mpcal::logio
