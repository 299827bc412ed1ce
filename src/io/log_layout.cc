#include "log_layout.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

#include <fast_float/fast_float.h>
#include <fmt/format.h>

#include "log_columns.h"
#include "mpcal/error.h"

namespace mpcal::logio {
namespace {

// Lines looked at to find the delimiter, header and time unit.
constexpr int kSniffLines = 2000;
constexpr int kDelimiterSniffLines = 50;

bool IsControl(unsigned char c) {
  return c < 0x20 && c != '\n' && c != '\r' && c != '\t' && c != '\f';
}

// Where the text starts: past serial noise (a NUL, control characters) in
// the first lines, as an Arduino sends while it boots; 0 when there is none,
// or when it does not end within the first 512 bytes on a line end (noise
// further in is a corrupt log, not a boot).
std::size_t NoiseEnd(std::string_view head) {
  constexpr std::size_t kBootBytes = 512;
  const std::size_t n = std::min<std::size_t>(head.size(), kBootBytes);
  std::size_t last_noise = n;
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<unsigned char>(head[i]);
    if (c == 0 || IsControl(c)) last_noise = i;
  }
  if (last_noise == n) return 0;
  const std::size_t nl = head.substr(0, n).find('\n', last_noise);
  if (nl == std::string_view::npos) return 0;
  const std::size_t start = nl + 1;
  // Some text must follow, or this is a binary file.
  return start + 64 <= head.size() ? start : 0;
}

// Throws when the first bytes (from `from`) are not text.
void CheckText(std::string_view head, std::size_t from, const std::string& source) {
  const std::size_t n = std::min<std::size_t>(head.size(), from + 65536);
  std::size_t controls = 0;
  for (std::size_t i = from; i < n; ++i) {
    const auto c = static_cast<unsigned char>(head[i]);
    if (c == 0) {
      throw Error(ErrorKind::kInput,
                  fmt::format("'{}' is not a text log (binary data at byte {}); mpcal "
                              "reads delimited text (CSV, TSV or whitespace separated "
                              "numbers)",
                              source,
                              i));
    }
    if (IsControl(c)) ++controls;
  }
  if (controls * 100 > n - from) {
    throw Error(ErrorKind::kInput,
                fmt::format("'{}' is not a text log (control characters in its first "
                            "bytes); mpcal reads delimited text (CSV, TSV or whitespace "
                            "separated numbers)",
                            source));
  }
  const std::string_view text = head.substr(from, n - from);
  if (text.find('\n') == std::string_view::npos &&
      std::count(text.begin(), text.end(), '\r') > 1) {
    throw Error(ErrorKind::kInput,
                fmt::format("'{}' ends its lines with a carriage return alone (classic "
                            "Mac OS); mpcal reads LF or CRLF line ends: convert it with "
                            "tr '\\r' '\\n' < '{}' > fixed.csv",
                            source,
                            source));
  }
}

// Fields of a line whatever separates them, and how many are numbers.
std::pair<std::size_t, std::size_t> CountFields(std::string_view text) {
  std::size_t fields = 0;
  std::size_t numbers = 0;
  std::size_t i = 0;
  while (i < text.size()) {
    while (i < text.size() && std::strchr(",; \t\r", text[i]) != nullptr) ++i;
    const std::size_t start = i;
    while (i < text.size() && std::strchr(",; \t\r", text[i]) == nullptr) ++i;
    if (i == start) break;
    ++fields;
    if (ParsesAsNumber(text.substr(start, i - start), '.')) ++numbers;
  }
  return {fields, numbers};
}

// Fields of a number row, whatever separates them.
std::size_t FieldCount(std::string_view text) { return CountFields(text).first; }

// A data row with a bad field ("0.2,4,abc,5"): mostly numbers. Such a line
// before the data is a log's own error, never boot text to skip.
bool IsMostlyNumbers(std::string_view text) {
  const auto [fields, numbers] = CountFields(text);
  return fields >= 3 && 2 * numbers >= fields;
}

// A content line (not a comment or blank) of the first chunk.
struct Sniffed {
  std::size_t line;  // 1-based, counted from the start of the text
  std::string_view text;
};

// The line above the first number row is a header when it has the rows'
// separator (or, for blank-separated rows, at least three fields).
bool IsHeaderAbove(std::string_view row, std::string_view above) {
  for (char d : {'\t', ';', ','}) {
    if (row.find(d) != std::string_view::npos) {
      return above.find(d) != std::string_view::npos;
    }
  }
  return SplitFields(above, ' ').size() >= 3;
}

// Finds the layout; one object per detection.
class Sniffer {
 public:
  Sniffer(std::string_view head,
          bool whole_input,
          const std::string& source,
          const LogOptions& options)
      : head_(head), eof_(whole_input), source_(source), options_(options) {}

  DetectedLayout Run(bool parse_gyro);

 private:
  std::vector<Sniffed> ContentLines() const;
  void SkipBootText(std::vector<Sniffed>* lines, std::size_t noise_end);
  std::size_t FirstNumberRun(const std::vector<Sniffed>& lines,
                             std::size_t from = 0) const;
  void WarnSkipped(std::size_t start_line, bool header);
  void FindSeparators(const std::vector<Sniffed>& lines);
  std::size_t FindHeader(const std::vector<Sniffed>& lines);
  void FindTimeUnit(const std::vector<Sniffed>& lines, std::size_t first_data);
  TimeUnit GuessIntegerUnit(const std::vector<std::string_view>& time_fields);
  void AssignRoles(bool parse_gyro);

  std::string_view head_;  // from the start of the input
  bool eof_;
  const std::string& source_;
  LogOptions options_;
  std::size_t begin_ = 0;  // after the byte-order mark
  DetectedLayout out_;
};

std::vector<Sniffed> Sniffer::ContentLines() const {
  std::vector<Sniffed> lines;
  std::size_t pos = begin_;
  std::size_t number = 0;
  while (pos < head_.size() && static_cast<int>(lines.size()) < kSniffLines) {
    const std::size_t nl = head_.find('\n', pos);
    if (nl == std::string_view::npos && !eof_) break;  // incomplete: not needed
    const std::size_t stop = nl == std::string_view::npos ? head_.size() : nl;
    std::string_view text = head_.substr(pos, stop - pos);
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    ++number;
    if (!IsCommentOrBlank(text)) lines.push_back({number, text});
    pos = stop + 1;
  }
  return lines;
}

// The index of the first of three number rows in a row; lines.size() if none.
std::size_t Sniffer::FirstNumberRun(const std::vector<Sniffed>& lines,
                                    std::size_t from) const {
  for (std::size_t i = from; i + 2 < lines.size() || (i < lines.size() && eof_); ++i) {
    bool run = true;
    for (std::size_t k = i; k < std::min(i + 3, lines.size()) && run; ++k) {
      run = IsNumberRow(lines[k].text);
    }
    if (run) return i;
  }
  return lines.size();
}

// A serial stream opened in the middle of a line starts with the line's
// tail: numbers only, fewer fields than the rows of the first run of data
// (`run`, three rows that agree among themselves), whether boot text
// follows it (a board that resets when its port is opened) or not. Only
// the first content line can be one.
bool IsCutLine(const std::vector<Sniffed>& lines, std::size_t i, std::size_t run) {
  if (run <= i || run + 2 >= lines.size()) return false;
  const std::size_t fields = FieldCount(lines[run].text);
  const auto [tail_fields, tail_numbers] = CountFields(lines[i].text);
  if (tail_fields == 0 || tail_numbers != tail_fields || tail_fields >= fields) {
    return false;
  }
  for (std::size_t k = run + 1; k <= run + 2; ++k) {
    if (FieldCount(lines[k].text) != fields) return false;
  }
  return true;
}

// Serial boot text before the header ("Initializing I2C devices...", a
// partial line): the lines before the first run of three number rows and
// the line just above it (the header, when it has the rows' separator) are
// skipped, with a warning that says where the data starts; so is a first
// line cut short (IsCutLine), never a header. Only when such a
// run exists: a log that never has one keeps its own errors.
void Sniffer::SkipBootText(std::vector<Sniffed>* lines, std::size_t noise_end) {
  std::size_t noise_lines = 0;
  if (noise_end > 0) {
    noise_lines = static_cast<std::size_t>(
        std::count(head_.begin() + begin_, head_.begin() + noise_end, '\n'));
  }
  std::size_t data = FirstNumberRun(*lines);
  // Lines within the serial noise never count, whatever follows.
  std::size_t first = 0;
  while (first < lines->size() && (*lines)[first].line <= noise_lines) ++first;
  const std::size_t run = data == first ? FirstNumberRun(*lines, first + 1) : data;
  const bool cut = data >= first && IsCutLine(*lines, first, run);
  if (cut) data = run;
  if (data == lines->size() || data < first) {
    if (first > 0) lines->erase(lines->begin(), lines->begin() + first);
    out_.skipped_lines = noise_lines;
    out_.skipped_bytes = noise_end;
    if (noise_lines > 0) WarnSkipped(lines->empty() ? 0 : lines->front().line, false);
    return;
  }
  std::size_t start = data;
  if (data > first + (cut ? 1 : 0) &&
      IsHeaderAbove((*lines)[data].text, (*lines)[data - 1].text)) {
    start = data - 1;
  }
  if (start == 0 && noise_lines == 0) return;
  bool at_header = start < data;
  for (std::size_t i = first + (cut ? 1 : 0); i < start; ++i) {
    if (IsMostlyNumbers((*lines)[i].text)) {
      start = first;
      at_header = false;
      break;
    }
  }
  if (start == 0 && noise_lines == 0) return;
  const std::size_t start_line = (*lines)[start].line;
  // Bytes of the lines before start_line, from the text's start.
  std::size_t pos = begin_;
  for (std::size_t line = 1; line < start_line; ++line) pos = head_.find('\n', pos) + 1;
  out_.skipped_lines = start_line - 1;
  out_.skipped_bytes = pos;
  lines->erase(lines->begin(), lines->begin() + start);
  if (out_.skipped_lines > 0) WarnSkipped(start_line, at_header);
}

void Sniffer::WarnSkipped(std::size_t start_line, bool header) {
  const std::size_t n = out_.skipped_lines;
  const char* what = header ? "header" : "data";
  out_.warnings.push_back(fmt::format(
      "'{}': skipped {} line{} before the {} (serial boot text or a title); the {} "
      "starts on line {}",
      source_,
      n,
      n == 1 ? "" : "s",
      what,
      what,
      start_line));
}

// Delimiter: the first of tab, semicolon, comma present in every sniffed
// line (semicolon before comma for decimal-comma logs), else blanks; then
// the decimal point, a comma only when the comma is not the delimiter.
void Sniffer::FindSeparators(const std::vector<Sniffed>& lines) {
  const std::size_t sniff = std::min<std::size_t>(lines.size(), kDelimiterSniffLines);
  auto everywhere = [&](char c) {
    for (std::size_t i = 0; i < sniff; ++i) {
      if (lines[i].text.find(c) == std::string_view::npos) return false;
    }
    return true;
  };
  auto anywhere = [&](char c) {
    for (std::size_t i = 0; i < sniff; ++i) {
      if (lines[i].text.find(c) != std::string_view::npos) return true;
    }
    return false;
  };
  char delimiter = ' ';
  for (char candidate : {'\t', ';', ','}) {
    if (everywhere(candidate)) {
      delimiter = candidate;
      break;
    }
  }
  // Tabs used for alignment (several in a row) behave like blanks.
  if (delimiter == '\t') {
    bool names_with_spaces = false;
    for (std::size_t i = 0; i < sniff; ++i) {
      for (auto f : SplitFields(lines[i].text, '\t')) {
        if (f.find(' ') != std::string_view::npos) names_with_spaces = true;
      }
    }
    if (!names_with_spaces) delimiter = ' ';
  }
  out_.layout.delimiter = delimiter;
  out_.layout.decimal_point =
      delimiter != ',' && anywhere(',') && !anywhere('.') ? ',' : '.';
}

// Header: the first content line when it is not all numbers. Returns the
// index of the first data line.
std::size_t Sniffer::FindHeader(const std::vector<Sniffed>& lines) {
  LogLayout& layout = out_.layout;
  auto text_fields = [&](std::string_view text) {
    std::vector<std::string_view> out;
    for (auto f : SplitFields(text, layout.delimiter)) {
      if (!ParsesAsNumber(f, layout.decimal_point)) out.push_back(f);
    }
    return out;
  };
  const auto first_text = text_fields(lines[0].text);
  if (first_text.empty()) return 0;
  layout.header_line = lines[0].line;
  for (auto f : SplitFields(lines[0].text, layout.delimiter)) {
    layout.column_names.emplace_back(StripQuotes(f));
  }
  if (lines.size() == 1) {
    if (eof_) {
      throw Error(
          ErrorKind::kInput,
          fmt::format("'{}' has a header (line {}: '{}') but no data rows after it",
                      source_,
                      lines[0].line,
                      Printable(lines[0].text, 60)));
    }
  } else if (const auto second_text = text_fields(lines[1].text);
             second_text.size() >= first_text.size()) {
    // A header names columns that the rows below fill with numbers (a note
    // column may stay text); two lines as wordy as each other are prose or
    // an unsupported format.
    throw Error(ErrorKind::kInput,
                fmt::format("{}:{}: expected a row of numbers separated by {}, found "
                            "'{}' ('{}' is not a number); is this an accelerometer log?",
                            source_,
                            lines[1].line,
                            DelimiterName(layout.delimiter),
                            Printable(lines[1].text, 60),
                            Printable(second_text.front())));
  }
  return 1;
}

// The unit that makes integer timestamps' typical spacing most like an
// IMU's sample period; kSeconds when they are not integers.
TimeUnit Sniffer::GuessIntegerUnit(const std::vector<std::string_view>& time_fields) {
  const LogLayout& layout = out_.layout;
  bool integers = !time_fields.empty();
  for (auto f : time_fields) integers = integers && LooksLikeInteger(f);
  if (!integers) return TimeUnit::kSeconds;
  std::vector<double> diffs;
  double previous = std::numeric_limits<double>::quiet_NaN();
  for (auto f : time_fields) {
    f = Trim(f);
    if (!f.empty() && f.front() == '+') f.remove_prefix(1);
    double v = 0;
    fast_float::from_chars(f.data(), f.data() + f.size(), v);
    if (v > previous) diffs.push_back(v - previous);
    previous = v;
  }
  if (diffs.empty()) return TimeUnit::kSeconds;
  std::nth_element(diffs.begin(), diffs.begin() + diffs.size() / 2, diffs.end());
  const double spacing = diffs[diffs.size() / 2];
  const bool steps_by_one =
      std::all_of(diffs.begin(), diffs.end(), [](double d) { return d == 1.0; });
  if (spacing == 1.0 && options_.rate_hz > 0.0) return TimeUnit::kSampleIndex;
  if (steps_by_one && diffs.size() >= 8) {
    // 0, 1, 2, ... is a sample counter (an ADXL345 sketch's `n`), not
    // milliseconds: read as ms it would blame the hold times.
    throw Error(ErrorKind::kTime,
                fmt::format("'{}': column '{}' steps by exactly 1 on every row: it is a "
                            "sample index, not a time: the sample rate is needed (or "
                            "the time unit, if it holds milliseconds at 1 kHz)",
                            source_,
                            layout.column_names[layout.time_column]),
                Give({{Option::kLogRate, ""}, {Option::kLogTimeUnit, "ms"}}));
  }
  // The unit that makes the sample period most like an IMU's (10 ms, on a
  // log scale), among periods from 50 µs to 2 s.
  TimeUnit unit = TimeUnit::kSeconds;
  double unit_seconds = 1.0;
  double best = std::numeric_limits<double>::infinity();
  for (auto [candidate, seconds] : {std::pair{TimeUnit::kNanoseconds, 1e-9},
                                    std::pair{TimeUnit::kMicroseconds, 1e-6},
                                    std::pair{TimeUnit::kMilliseconds, 1e-3}}) {
    const double period = spacing * seconds;
    if (period < 5e-5 || period > 2.0) continue;
    const double distance = std::abs(std::log10(period / 1e-2));
    if (distance < best) {
      best = distance;
      unit = candidate;
      unit_seconds = seconds;
    }
  }
  if (unit != TimeUnit::kSeconds) {
    out_.warnings.push_back(fmt::format(
        "integer timestamps in '{}' taken as {} (typical spacing {:g}, i.e. {:.4g} Hz); "
        "give the time unit if that is wrong",
        layout.column_names[layout.time_column],
        ToString(unit),
        spacing,
        1.0 / (spacing * unit_seconds)));
  }
  return unit;
}

void Sniffer::FindTimeUnit(const std::vector<Sniffed>& lines, std::size_t first_data) {
  LogLayout& layout = out_.layout;
  TimeUnit unit = options_.time_unit;
  if (layout.time_column < 0) unit = TimeUnit::kSampleIndex;
  // A unit in the column's name (`millis`, `Time (s)`) is the logger's word.
  if (unit == TimeUnit::kAuto && layout.header_line > 0 &&
      layout.time_column < static_cast<int>(layout.column_names.size())) {
    if (const auto named = TimeUnitOfName(layout.column_names[layout.time_column])) {
      unit = *named;
    }
  }
  if (unit == TimeUnit::kAuto) {
    std::vector<std::string_view> time_fields;
    for (std::size_t i = first_data; i < lines.size(); ++i) {
      const auto fields = SplitFields(lines[i].text, layout.delimiter);
      if (layout.time_column < static_cast<int>(fields.size())) {
        time_fields.push_back(fields[layout.time_column]);
      }
    }
    unit = GuessIntegerUnit(time_fields);
  }
  layout.time_unit = unit;
  switch (unit) {
    case TimeUnit::kSampleIndex:
      if (options_.rate_hz <= 0.0) {
        throw Error(
            ErrorKind::kTime,
            fmt::format(
                "'{}': the time column is a sample index, so the sample rate is needed",
                source_),
            Give({{Option::kLogRate, ""}}));
      }
      layout.seconds_per_time_unit = 1.0 / options_.rate_hz;
      break;
    case TimeUnit::kMilliseconds:
      layout.seconds_per_time_unit = 1e-3;
      break;
    case TimeUnit::kMicroseconds:
      layout.seconds_per_time_unit = 1e-6;
      break;
    case TimeUnit::kNanoseconds:
      layout.seconds_per_time_unit = 1e-9;
      break;
    default:
      layout.seconds_per_time_unit = 1.0;
  }
}

// The role of each column that is parsed; min_columns becomes the last one.
void Sniffer::AssignRoles(bool parse_gyro) {
  LogLayout& layout = out_.layout;
  std::vector<Role>& roles = out_.roles;
  roles.assign(layout.min_columns, kNone);
  if (layout.time_column >= 0) roles[layout.time_column] = kTime;
  for (int i = 0; i < 3; ++i) {
    roles[layout.accel_columns[i]] = static_cast<Role>(kAx + i);
    if (parse_gyro && layout.gyro_columns[i] >= 0) {
      roles[layout.gyro_columns[i]] = static_cast<Role>(kGx + i);
    }
  }
  int last_needed = 0;
  for (int c = 0; c < static_cast<int>(roles.size()); ++c) {
    if (roles[c] != kNone) last_needed = c;
  }
  layout.min_columns = last_needed + 1;
  roles.resize(layout.min_columns);
}

DetectedLayout Sniffer::Run(bool parse_gyro) {
  if (head_.empty()) {
    throw Error(ErrorKind::kInput,
                fmt::format("'{}' is empty: no data to read", source_));
  }
  const std::size_t noise_end = NoiseEnd(head_);
  CheckText(head_, noise_end, source_);
  // A UTF-8 byte-order mark (spreadsheet exports) is not part of the data.
  if (head_.starts_with("\xEF\xBB\xBF")) begin_ = out_.bom_bytes = 3;
  std::vector<Sniffed> lines = ContentLines();
  SkipBootText(&lines, noise_end);
  if (lines.empty()) {
    if (eof_) {
      throw Error(ErrorKind::kInput,
                  fmt::format("'{}' has no data: only comments or blank lines; expected "
                              "rows of numbers (t, ax, ay, az)",
                              source_));
    }
    throw Error(
        ErrorKind::kInput,
        fmt::format(
            "'{}': no data line in its first {} KiB", source_, head_.size() / 1024));
  }
  FindSeparators(lines);
  const std::size_t first_data = FindHeader(lines);
  LogLayout& layout = out_.layout;
  const std::size_t data_columns =
      first_data < lines.size()
          ? SplitFields(lines[first_data].text, layout.delimiter).size()
          : 0;
  if (layout.column_names.empty()) {
    for (std::size_t i = 0; i < data_columns; ++i) {
      layout.column_names.push_back(fmt::format("column {}", i));
    }
  }
  ResolveColumns(source_, data_columns, parse_gyro, &options_, &layout);
  if (first_data < lines.size() && static_cast<int>(data_columns) < layout.min_columns) {
    throw Error(ErrorKind::kColumns,
                fmt::format("{}:{}: too few columns: found {}, expected at least {} "
                            "separated by {} ({})",
                            source_,
                            lines[first_data].line,
                            data_columns,
                            layout.min_columns,
                            DelimiterName(layout.delimiter),
                            layout.Describe()));
  }
  FindTimeUnit(lines, first_data);
  AssignRoles(parse_gyro);
  return std::move(out_);
}

}  // namespace

bool IsNumberRow(std::string_view text) {
  const auto [fields, numbers] = CountFields(text);
  return fields >= 3 && numbers == fields;
}

DetectedLayout DetectLayout(std::string_view head,
                            bool whole_input,
                            const std::string& source,
                            const LogOptions& options,
                            bool parse_gyro) {
  return Sniffer(head, whole_input, source, options).Run(parse_gyro);
}

}  // namespace mpcal::logio
