#include "mpcal/log_reader.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <exception>
#include <limits>
#include <map>
#include <mutex>
#include <numbers>
#include <system_error>
#include <thread>
#include <utility>

#include <fast_float/fast_float.h>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "mpcal/error.h"
#include "mpcal/plausible.h"

namespace mpcal {
namespace {

// Large enough that the read(2) calls and the per-chunk bookkeeping vanish
// next to number parsing, small enough to stay in L2/L3 cache.
constexpr std::size_t kChunkBytes = std::size_t{1} << 20;
// A text log's line is at most a few hundred bytes; a longer one means the
// input is not a log (binary junk, or a file without line ends).
constexpr std::size_t kMaxLineBytes = std::size_t{1} << 19;
// Lines looked at to find the delimiter, header and time unit.
constexpr int kSniffLines = 2000;
constexpr int kDelimiterSniffLines = 50;

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

constexpr const char* kRoleKeys[] = {"", "t", "ax", "ay", "az", "gx", "gy", "gz"};

bool IsBlank(char c) { return c == ' ' || c == '\t'; }

std::string_view Trim(std::string_view s) {
  while (!s.empty() && (IsBlank(s.front()) || s.front() == '\r')) s.remove_prefix(1);
  while (!s.empty() && (IsBlank(s.back()) || s.back() == '\r')) s.remove_suffix(1);
  return s;
}

std::string_view StripQuotes(std::string_view s) {
  s = Trim(s);
  if (s.size() >= 2 && (s.front() == '"' || s.front() == '\'') && s.back() == s.front()) {
    s = s.substr(1, s.size() - 2);
  }
  return Trim(s);
}

std::string Lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) {
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  }
  return out;
}

// "Acc_X [m/s2]" -> "accx": case, separators and a bracketed unit do not
// matter for recognising a column.
std::string NormaliseName(std::string_view name) {
  std::string_view s = StripQuotes(name);
  const auto bracket = s.find_first_of("[(");
  if (bracket != std::string_view::npos && bracket > 0) s = s.substr(0, bracket);
  std::string out;
  for (char c : Lower(s)) {
    if (c == '_' || c == '-' || c == ' ' || c == '.' || c == '\t') continue;
    out.push_back(c);
  }
  return out;
}

Role RoleOfName(std::string_view name) {
  static const std::map<std::string, Role> kNames = [] {
    std::map<std::string, Role> m;
    for (const char* t : {"t", "time", "timestamp", "ts"}) m[t] = kTime;
    // Loggers name the time column after its unit: Arduino's millis() and
    // micros(), `timestamp_ms`, `time_us`, `Time (s)` (the bracket is
    // dropped by NormaliseName; TimeUnitOfName reads it).
    for (const char* t : {"millis",
                          "micros",
                          "nanos",
                          "times",
                          "timesec",
                          "timems",
                          "timeus",
                          "timens",
                          "tms",
                          "tus",
                          "tns",
                          "timestampms",
                          "timestampus",
                          "timestampns",
                          "timestamps",
                          "elapsed",
                          "elapsedms",
                          "elapsedus",
                          "seconds"}) {
      m[t] = kTime;
    }
    const char* axes = "xyz";
    for (int i = 0; i < 3; ++i) {
      for (std::string prefix : {"a", "acc", "accel", "acceleration", "accelerometer"}) {
        m[prefix + axes[i]] = static_cast<Role>(kAx + i);
      }
      for (std::string prefix : {"g", "gyr", "gyro", "gyroscope"}) {
        m[prefix + axes[i]] = static_cast<Role>(kGx + i);
      }
    }
    return m;
  }();
  const auto it = kNames.find(NormaliseName(name));
  return it == kNames.end() ? kNone : it->second;
}

// The unit a time column's name states: `millis`, `timestamp_ms`,
// `Time (s)`, `t [us]`; nullopt when it says none.
std::optional<TimeUnit> TimeUnitOfName(std::string_view name) {
  const std::string raw = Lower(StripQuotes(name));
  const auto bracket = raw.find_first_of("[(");
  if (bracket != std::string::npos && bracket > 0) {
    std::string inside;
    for (char c : raw.substr(bracket + 1)) {
      if (c == ')' || c == ']') break;
      if (c != ' ') inside.push_back(c);
    }
    if (inside == "s" || inside == "sec") return TimeUnit::kSeconds;
    if (inside == "ms") return TimeUnit::kMilliseconds;
    if (inside == "us" || inside == "\xc2\xb5s" || inside == "\xce\xbcs") {
      return TimeUnit::kMicroseconds;
    }
    if (inside == "ns") return TimeUnit::kNanoseconds;
  }
  const std::string n = NormaliseName(name);
  if (n == "millis" || n == "timems" || n == "tms" || n == "timestampms" ||
      n == "elapsedms") {
    return TimeUnit::kMilliseconds;
  }
  if (n == "micros" || n == "timeus" || n == "tus" || n == "timestampus" ||
      n == "elapsedus") {
    return TimeUnit::kMicroseconds;
  }
  if (n == "nanos" || n == "timens" || n == "tns" || n == "timestampns") {
    return TimeUnit::kNanoseconds;
  }
  if (n == "times" || n == "timesec" || n == "seconds") return TimeUnit::kSeconds;
  return std::nullopt;
}

bool IsSampleIndexName(std::string_view name) {
  const std::string n = NormaliseName(name);
  return n == "nsamples" || n == "sample" || n == "samples" || n == "sampleindex" ||
         n == "samplenumber" || n == "index" || n == "idx" || n == "counter";
}

std::string Printable(std::string_view s, std::size_t max = 40) {
  std::string out;
  for (char c : s.substr(0, max)) {
    const auto u = static_cast<unsigned char>(c);
    out += (u < 0x20 || u == 0x7f) ? std::string("?") : std::string(1, c);
  }
  if (s.size() > max) out += "...";
  return out;
}

std::string DelimiterName(char d) {
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

// Splits a line into fields (for sniffing only; the hot path never allocates).
std::vector<std::string_view> SplitFields(std::string_view line, char delimiter) {
  std::vector<std::string_view> fields;
  if (delimiter == ' ') {
    std::size_t i = 0;
    while (true) {
      while (i < line.size() && (IsBlank(line[i]) || line[i] == '\r')) ++i;
      if (i >= line.size()) break;
      const std::size_t start = i;
      while (i < line.size() && !IsBlank(line[i]) && line[i] != '\r') ++i;
      fields.push_back(line.substr(start, i - start));
    }
  } else {
    std::size_t start = 0;
    while (true) {
      const auto pos = line.find(delimiter, start);
      if (pos == std::string_view::npos) {
        fields.push_back(Trim(line.substr(start)));
        break;
      }
      fields.push_back(Trim(line.substr(start, pos - start)));
      start = pos + 1;
    }
  }
  return fields;
}

bool ParsesAsNumber(std::string_view field, char decimal_point) {
  field = StripQuotes(field);
  if (!field.empty() && field.front() == '+') field.remove_prefix(1);
  if (field.empty()) return false;
  double v = 0;
  const auto r = fast_float::from_chars_advanced(
      field.data(),
      field.data() + field.size(),
      v,
      fast_float::parse_options{fast_float::chars_format::general, decimal_point});
  return r.ec == std::errc() && r.ptr == field.data() + field.size();
}

bool LooksLikeInteger(std::string_view field) {
  field = StripQuotes(field);
  if (!field.empty() && (field.front() == '-' || field.front() == '+'))
    field.remove_prefix(1);
  if (field.empty()) return false;
  return std::all_of(
      field.begin(), field.end(), [](char c) { return c >= '0' && c <= '9'; });
}

struct ColumnSpec {
  Role role;
  std::string name;  // empty when given by index
  int index = -1;
};

// Parses "t=NAME|INDEX,ax=..."; returns "" or the problem.
std::string ParseColumnSpec(const std::string& spec, std::vector<ColumnSpec>* out) {
  std::vector<ColumnSpec> specs;
  std::size_t start = 0;
  while (start <= spec.size()) {
    auto end = spec.find(',', start);
    if (end == std::string::npos) end = spec.size();
    const std::string_view item = Trim(std::string_view(spec).substr(start, end - start));
    start = end + 1;
    if (item.empty()) {
      if (end == spec.size()) break;
      return "empty item (expected KEY=NAME|INDEX, e.g. t=time,ax=1)";
    }
    const auto eq = item.find('=');
    if (eq == std::string_view::npos) {
      return fmt::format("'{}' is not KEY=NAME|INDEX (e.g. ax=acc_x or ax=1)", item);
    }
    const std::string key = Lower(Trim(item.substr(0, eq)));
    const std::string_view value = Trim(item.substr(eq + 1));
    Role role = kNone;
    for (int r = kTime; r <= kGz; ++r) {
      if (key == kRoleKeys[r]) role = static_cast<Role>(r);
    }
    if (key == "time") role = kTime;
    if (role == kNone) {
      return fmt::format("unknown key '{}' (known: t, ax, ay, az, gx, gy, gz)", key);
    }
    if (value.empty()) return fmt::format("no column given for '{}'", key);
    for (const auto& s : specs) {
      if (s.role == role) return fmt::format("'{}' given twice", key);
    }
    ColumnSpec c{role, "", -1};
    if (LooksLikeInteger(value) && value.front() != '-' && value.front() != '+') {
      if (value.size() > 6) return fmt::format("column index {} is too large", value);
      c.index = std::stoi(std::string(value));
    } else {
      c.name = std::string(value);
    }
    specs.push_back(c);
    if (end == spec.size()) break;
  }
  if (out) *out = std::move(specs);
  return "";
}

}  // namespace

std::string_view ToString(TimeUnit unit) {
  switch (unit) {
    case TimeUnit::kAuto:
      return "auto";
    case TimeUnit::kSeconds:
      return "s";
    case TimeUnit::kMilliseconds:
      return "ms";
    case TimeUnit::kMicroseconds:
      return "us";
    case TimeUnit::kNanoseconds:
      return "ns";
    case TimeUnit::kSampleIndex:
      return "index";
  }
  return "unknown";
}

std::optional<TimeUnit> ParseTimeUnit(std::string_view name) {
  const std::string n = Lower(name);
  if (n == "auto") return TimeUnit::kAuto;
  if (n == "s") return TimeUnit::kSeconds;
  if (n == "ms") return TimeUnit::kMilliseconds;
  if (n == "us" || n == "\xc2\xb5s") return TimeUnit::kMicroseconds;
  if (n == "ns") return TimeUnit::kNanoseconds;
  if (n == "index") return TimeUnit::kSampleIndex;
  return std::nullopt;
}

std::string LogOptions::Validate() const {
  if (!std::isfinite(rate_hz) || rate_hz < 0.0) {
    return fmt::format("rate_hz must be a positive number of Hz (or 0 for none), got {}",
                       rate_hz);
  }
  if (time_unit == TimeUnit::kSampleIndex && rate_hz <= 0.0) {
    return "time_unit 'index' needs the sample rate: give rate_hz (--rate HZ)";
  }
  const std::string columns_problem = ParseColumnSpec(columns, nullptr);
  if (!columns_problem.empty()) return "columns: " + columns_problem;
  return "";
}

std::string LogLayout::Describe() const {
  std::string out;
  auto add = [&](const char* key, int column) {
    if (column < 0) return;
    if (!out.empty()) out += ", ";
    const std::string name =
        column < static_cast<int>(column_names.size()) ? column_names[column] : "";
    out += header_line > 0 ? fmt::format("{} = '{}' (index {})", key, name, column)
                           : fmt::format("{} = index {}", key, column);
  };
  add("t", time_column);
  add("ax", accel_columns[0]);
  add("ay", accel_columns[1]);
  add("az", accel_columns[2]);
  add("gx", gyro_columns[0]);
  add("gy", gyro_columns[1]);
  add("gz", gyro_columns[2]);
  return out;
}

namespace {

// The layout found from a log's first lines and the parser of its lines:
// LogScanner's state, and ReadLog's, which parses chunks on two threads.
struct ScannerState {
  std::string source;
  int fd = -1;
  bool owns_fd = false;
  std::vector<char> buf;
  std::size_t begin = 0;  // first unconsumed byte
  std::size_t end = 0;    // one past the last byte read
  bool eof = false;
  std::uint64_t bytes_from_fd = 0;
  std::uint64_t consumed = 0;
  std::uint64_t total = 0;
  std::size_t line_number = 0;
  std::size_t data_rows = 0;
  LogLayout layout;
  LogOptions options;
  // The largest reading an accelerometer gives, in options.units.
  double max_reading = kMaxReadingCounts;
  // Boot text skipped before the header or data: lines, and bytes from the
  // start of the input (ReadLog starts there; LogScanner passes them on).
  std::size_t skipped_lines = 0;
  std::size_t skipped_bytes = 0;
  std::vector<Role> roles;  // role of each column up to min_columns
  int last_needed = 0;      // last column index that is parsed
  fast_float::parse_options number_format;
  std::vector<std::string> warnings;
  double last_progress = -1.0;

  ScannerState() = default;
  ScannerState(const ScannerState&) = delete;
  ScannerState& operator=(const ScannerState&) = delete;
  ~ScannerState() {
    if (owns_fd && fd >= 0) ::close(fd);
  }

  void Open(const std::string& path) {
    if (path == "-") {
      source = "<stdin>";
      fd = STDIN_FILENO;
      return;
    }
    source = path;
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0) {
      const int err = errno;
      throw Error(fmt::format("cannot read log '{}': {}{}",
                              path,
                              std::strerror(err),
                              err == ENOENT ? " (check the path)" : ""));
    }
    if (S_ISDIR(st.st_mode)) {
      throw Error(fmt::format("'{}' is a directory; give the path of a log file", path));
    }
    fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
      throw Error(fmt::format("cannot read log '{}': {}", path, std::strerror(errno)));
    }
    owns_fd = true;
    if (S_ISREG(st.st_mode)) {
      total = static_cast<std::uint64_t>(st.st_size);
#ifdef POSIX_FADV_SEQUENTIAL
      ::posix_fadvise(fd, 0, 0, POSIX_FADV_SEQUENTIAL);
#endif
    }
  }

  // Reads more input after the unconsumed bytes; `fill`: until the buffer is
  // full or the input ends (pipes deliver a little at a time).
  void Refill(bool fill) {
    if (begin > 0) {
      std::memmove(buf.data(), buf.data() + begin, end - begin);
      end -= begin;
      begin = 0;
    }
    if (end == buf.size()) buf.resize(buf.size() * 2);
    while (!eof && end < buf.size()) {
      const ssize_t n = ::read(fd, buf.data() + end, buf.size() - end);
      if (n < 0) {
        if (errno == EINTR) continue;
        throw Error(fmt::format("error reading '{}': {}", source, std::strerror(errno)));
      }
      if (n == 0) {
        eof = true;
        break;
      }
      end += static_cast<std::size_t>(n);
      bytes_from_fd += static_cast<std::uint64_t>(n);
      if (!fill) break;
    }
    if (options.progress && total > 0) {
      const double fraction = std::min(1.0, static_cast<double>(bytes_from_fd) / total);
      if (fraction - last_progress >= 0.01 || (eof && last_progress < 1.0)) {
        last_progress = fraction;
        options.progress(fraction);
      }
    }
  }

  // The next raw line (text without its end) or false at the end of input.
  bool GetLine(std::string_view* text, std::string_view* eol) {
    while (true) {
      const char* start = buf.data() + begin;
      const auto* nl = static_cast<const char*>(std::memchr(start, '\n', end - begin));
      if (nl != nullptr) {
        const std::size_t len = static_cast<std::size_t>(nl - start);
        const bool cr = len > 0 && nl[-1] == '\r';
        *text = std::string_view(start, cr ? len - 1 : len);
        *eol = std::string_view(cr ? nl - 1 : nl, cr ? 2 : 1);
        begin += len + 1;
        consumed += len + 1;
        ++line_number;
        return true;
      }
      if (eof) {
        if (begin == end) return false;
        std::size_t len = end - begin;
        const bool cr = start[len - 1] == '\r';
        *text = std::string_view(start, cr ? len - 1 : len);
        *eol = cr ? std::string_view(start + len - 1, 1) : std::string_view();
        begin = end;
        consumed += len;
        ++line_number;
        return true;
      }
      if (end - begin >= kMaxLineBytes) {
        throw Error(fmt::format(
            "{}:{}: line longer than {} KiB: this does not look like a text log",
            source,
            line_number + 1,
            kMaxLineBytes / 1024));
      }
      Refill(false);
    }
  }

  // Where the text starts: past serial noise (a NUL, control characters)
  // in the first lines, as an Arduino sends while it boots; 0 when there is
  // none, or when it does not end within the first 512 bytes on a line end
  // (noise further in is a corrupt log, not a boot).
  std::size_t NoiseEnd() const {
    constexpr std::size_t kBootBytes = 512;
    const std::size_t n = std::min<std::size_t>(end, kBootBytes);
    std::size_t last_noise = n;
    for (std::size_t i = 0; i < n; ++i) {
      const auto c = static_cast<unsigned char>(buf[i]);
      if (c == 0 || (c < 0x20 && c != '\n' && c != '\r' && c != '\t' && c != '\f')) {
        last_noise = i;
      }
    }
    if (last_noise == n) return 0;
    const auto* nl = static_cast<const char*>(std::memchr(
        buf.data() + last_noise, '\n', std::min(end, kBootBytes) - last_noise));
    if (nl == nullptr) return 0;
    const std::size_t start = static_cast<std::size_t>(nl - buf.data()) + 1;
    // Some text must follow, or this is a binary file.
    return start + 64 <= end ? start : 0;
  }

  // Throws when the first bytes (from `from`) are not text.
  void CheckText(std::size_t from = 0) {
    const std::size_t n = std::min<std::size_t>(end, from + 65536);
    std::size_t controls = 0;
    for (std::size_t i = from; i < n; ++i) {
      const auto c = static_cast<unsigned char>(buf[i]);
      if (c == 0) {
        throw Error(fmt::format(
            "'{}' is not a text log (binary data at byte {}); mpcal reads delimited text "
            "(CSV, TSV or whitespace separated numbers)",
            source,
            i));
      }
      if (c < 0x20 && c != '\n' && c != '\r' && c != '\t' && c != '\f') ++controls;
    }
    if (controls * 100 > n - from) {
      throw Error(fmt::format(
          "'{}' is not a text log (control characters in its first bytes); mpcal reads "
          "delimited text (CSV, TSV or whitespace separated numbers)",
          source));
    }
    const std::string_view head(buf.data() + from, n - from);
    if (head.find('\n') == std::string_view::npos &&
        std::count(head.begin(), head.end(), '\r') > 1) {
      throw Error(fmt::format(
          "'{}' ends its lines with a carriage return alone (classic Mac OS); mpcal "
          "reads "
          "LF or CRLF line ends: convert it with tr '\\r' '\\n' < '{}' > fixed.csv",
          source,
          source));
    }
  }

  static bool IsCommentOrBlank(std::string_view text) {
    std::size_t i = 0;
    while (i < text.size() && (IsBlank(text[i]) || text[i] == '\r' || text[i] == '\f'))
      ++i;
    return i == text.size() || text[i] == '#' || text[i] == '%';
  }

  // Fields of a line whatever separates them, and how many are numbers.
  static std::pair<std::size_t, std::size_t> CountFields(std::string_view text) {
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
  // A line of at least 3 numbers and nothing else.
  static bool IsNumberRow(std::string_view text) {
    const auto [fields, numbers] = CountFields(text);
    return fields >= 3 && numbers == fields;
  }
  // A data row with a bad field ("0.2,4,abc,5"): mostly numbers. Such a line
  // before the data is a log's own error, never boot text to skip.
  static bool IsMostlyNumbers(std::string_view text) {
    const auto [fields, numbers] = CountFields(text);
    return fields >= 3 && 2 * numbers >= fields;
  }

  // Serial boot text before the header ("Initializing I2C devices...", a
  // partial line): the lines before the first run of three number rows and
  // the line just above it (the header, when it has the rows' separator)
  // are skipped, with a warning that says where the data starts. Only when
  // such a run exists: a log that never has one keeps its own errors.
  template <typename Sniffed>
  void SkipBootText(std::vector<Sniffed>* lines, std::size_t noise_end) {
    std::size_t noise_lines = 0;
    if (noise_end > 0) {
      noise_lines = static_cast<std::size_t>(
          std::count(buf.data() + begin, buf.data() + noise_end, '\n'));
    }
    std::size_t data = lines->size();
    for (std::size_t i = 0; i + 2 < lines->size() || (i < lines->size() && eof); ++i) {
      bool run = true;
      for (std::size_t k = i; k < std::min(i + 3, lines->size()) && run; ++k) {
        run = IsNumberRow((*lines)[k].text);
      }
      if (run) {
        data = i;
        break;
      }
    }
    // Lines within the serial noise never count, whatever follows.
    std::size_t first = 0;
    while (first < lines->size() && (*lines)[first].line <= noise_lines) ++first;
    if (data == lines->size() || data < first) {
      if (first > 0) lines->erase(lines->begin(), lines->begin() + first);
      skipped_lines = noise_lines;
      skipped_bytes = noise_end;
      if (noise_lines > 0) WarnSkipped(lines->empty() ? 0 : lines->front().line, false);
      return;
    }
    std::size_t start = data;
    if (data > first) {
      const std::string_view row = (*lines)[data].text;
      const std::string_view above = (*lines)[data - 1].text;
      bool header = false;
      for (char d : {'\t', ';', ','}) {
        if (row.find(d) != std::string_view::npos) {
          header = above.find(d) != std::string_view::npos;
          break;
        }
      }
      if (!header && row.find_first_of("\t;,") == std::string_view::npos) {
        header = SplitFields(above, ' ').size() >= 3;
      }
      if (header) start = data - 1;
    }
    if (start == 0 && noise_lines == 0) return;
    bool at_header = start < data;
    for (std::size_t i = first; i < start; ++i) {
      if (IsMostlyNumbers((*lines)[i].text)) {
        start = first;
        at_header = false;
        break;
      }
    }
    if (start == 0 && noise_lines == 0) return;
    const std::size_t start_line = (*lines)[start].line;
    // Bytes of the lines before start_line, from the unconsumed start.
    std::size_t pos = begin;
    for (std::size_t line = 1; line < start_line; ++line) {
      const auto* nl =
          static_cast<const char*>(std::memchr(buf.data() + pos, '\n', end - pos));
      pos = static_cast<std::size_t>(nl - buf.data()) + 1;
    }
    skipped_lines = start_line - 1;
    skipped_bytes = pos;
    lines->erase(lines->begin(), lines->begin() + start);
    if (skipped_lines > 0) WarnSkipped(start_line, at_header);
  }

  void WarnSkipped(std::size_t start_line, bool header) {
    warnings.push_back(
        fmt::format("'{}': skipped {} line{} before the {} (serial boot text or a "
                    "title); the {} starts "
                    "on line {}",
                    source,
                    skipped_lines,
                    skipped_lines == 1 ? "" : "s",
                    header ? "header" : "data",
                    header ? "header" : "data",
                    start_line));
  }

  void Detect(bool parse_gyro) {
    buf.resize(kChunkBytes);
    Refill(true);
    if (end == 0) throw Error(fmt::format("'{}' is empty: no data to read", source));
    const std::size_t noise_end = NoiseEnd();
    CheckText(noise_end);
    // A UTF-8 byte-order mark (spreadsheet exports) is not part of the data.
    if (end >= 3 && std::memcmp(buf.data(), "\xEF\xBB\xBF", 3) == 0) {
      begin = 3;
      consumed = 3;
    }

    // The content lines (not comments or blank) of the first chunk.
    struct Sniffed {
      std::size_t line;
      std::string_view text;
    };
    std::vector<Sniffed> lines;
    {
      std::size_t pos = begin;
      std::size_t number = 0;
      while (pos < end && static_cast<int>(lines.size()) < kSniffLines) {
        const auto* nl =
            static_cast<const char*>(std::memchr(buf.data() + pos, '\n', end - pos));
        if (nl == nullptr && !eof) break;  // incomplete line: not needed to sniff
        const std::size_t stop = nl ? static_cast<std::size_t>(nl - buf.data()) : end;
        std::string_view text(buf.data() + pos, stop - pos);
        if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
        ++number;
        if (!IsCommentOrBlank(text)) lines.push_back({number, text});
        pos = stop + 1;
      }
    }
    SkipBootText(&lines, noise_end);
    if (lines.empty()) {
      if (eof) {
        throw Error(fmt::format(
            "'{}' has no data: only comments or blank lines; expected rows of numbers "
            "(t, ax, ay, az)",
            source));
      }
      throw Error(fmt::format(
          "'{}': no data line in its first {} KiB", source, kChunkBytes / 1024));
    }

    // Delimiter: the first of tab, semicolon, comma present in every sniffed
    // line (semicolon before comma for decimal-comma logs), else blanks.
    const std::size_t sniff = std::min<std::size_t>(lines.size(), kDelimiterSniffLines);
    char delimiter = ' ';
    for (char candidate : {'\t', ';', ','}) {
      bool everywhere = true;
      for (std::size_t i = 0; i < sniff && everywhere; ++i) {
        everywhere = lines[i].text.find(candidate) != std::string_view::npos;
      }
      if (everywhere) {
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
    layout.delimiter = delimiter;

    // Decimal commas: only possible when the comma is not the delimiter.
    char decimal_point = '.';
    if (delimiter != ',') {
      bool comma = false;
      bool dot = false;
      for (std::size_t i = 0; i < sniff; ++i) {
        comma |= lines[i].text.find(',') != std::string_view::npos;
        dot |= lines[i].text.find('.') != std::string_view::npos;
      }
      if (comma && !dot) decimal_point = ',';
    }
    layout.decimal_point = decimal_point;
    number_format =
        fast_float::parse_options{fast_float::chars_format::general, decimal_point};

    // Header: the first content line when it is not all numbers.
    auto text_fields = [&](std::string_view text) {
      std::vector<std::string_view> out;
      for (auto f : SplitFields(text, delimiter)) {
        if (!ParsesAsNumber(f, decimal_point)) out.push_back(f);
      }
      return out;
    };
    std::size_t first_data = 0;
    const auto first_text = text_fields(lines[0].text);
    if (!first_text.empty()) {
      layout.header_line = lines[0].line;
      for (auto f : SplitFields(lines[0].text, delimiter)) {
        layout.column_names.emplace_back(StripQuotes(f));
      }
      first_data = 1;
      if (lines.size() == 1) {
        if (eof) {
          throw Error(
              fmt::format("'{}' has a header (line {}: '{}') but no data rows after it",
                          source,
                          lines[0].line,
                          Printable(lines[0].text, 60)));
        }
      } else if (const auto second_text = text_fields(lines[1].text);
                 second_text.size() >= first_text.size()) {
        // A header names columns that the rows below fill with numbers (a
        // note column may stay text); two lines as wordy as each other are
        // prose or an unsupported format.
        throw Error(fmt::format(
            "{}:{}: expected a row of numbers separated by {}, found '{}' ('{}' is not a "
            "number); is this an accelerometer log?",
            source,
            lines[1].line,
            DelimiterName(delimiter),
            Printable(lines[1].text, 60),
            Printable(second_text.front())));
      }
    }
    const std::size_t first_data_columns =
        first_data < lines.size() ? SplitFields(lines[first_data].text, delimiter).size()
                                  : 0;
    if (layout.column_names.empty()) {
      for (std::size_t i = 0; i < first_data_columns; ++i) {
        layout.column_names.push_back(fmt::format("column {}", i));
      }
    }

    ResolveColumns(first_data_columns, parse_gyro);
    if (first_data < lines.size() &&
        static_cast<int>(first_data_columns) < layout.min_columns) {
      throw Error(fmt::format(
          "{}:{}: too few columns: found {}, expected at least {} separated by {} ({})",
          source,
          lines[first_data].line,
          first_data_columns,
          layout.min_columns,
          DelimiterName(delimiter),
          layout.Describe()));
    }

    std::vector<std::string_view> time_fields;
    if (layout.time_column >= 0) {
      for (std::size_t i = first_data; i < lines.size(); ++i) {
        const auto fields = SplitFields(lines[i].text, delimiter);
        if (layout.time_column < static_cast<int>(fields.size())) {
          time_fields.push_back(fields[layout.time_column]);
        }
      }
    }
    ResolveTimeUnit(time_fields);

    roles.assign(layout.min_columns, kNone);
    if (layout.time_column >= 0) roles[layout.time_column] = kTime;
    for (int i = 0; i < 3; ++i) {
      roles[layout.accel_columns[i]] = static_cast<Role>(kAx + i);
      if (parse_gyro && layout.gyro_columns[i] >= 0) {
        roles[layout.gyro_columns[i]] = static_cast<Role>(kGx + i);
      }
    }
    last_needed = 0;
    for (int c = 0; c < static_cast<int>(roles.size()); ++c) {
      if (roles[c] != kNone) last_needed = c;
    }
    layout.min_columns = last_needed + 1;
    roles.resize(layout.min_columns);
  }

  void ResolveColumns(std::size_t data_columns, bool parse_gyro) {
    std::vector<ColumnSpec> specs;
    const std::string problem = ParseColumnSpec(options.columns, &specs);
    if (!problem.empty()) throw Error("--columns: " + problem);
    const bool header = layout.header_line > 0;
    std::array<int, 8> column;
    column.fill(-1);
    // From the header's names first, then the explicit mapping over them.
    int sample_index_column = -1;
    if (header) {
      for (int c = 0; c < static_cast<int>(layout.column_names.size()); ++c) {
        const Role r = RoleOfName(layout.column_names[c]);
        if (r != kNone && column[r] < 0) column[r] = c;
        if (r == kNone && sample_index_column < 0 &&
            IsSampleIndexName(layout.column_names[c])) {
          sample_index_column = c;
        }
      }
      for (auto& spec : specs) {
        if (spec.index < 0) {
          const std::string wanted = Lower(spec.name);
          for (int c = 0; c < static_cast<int>(layout.column_names.size()); ++c) {
            if (Lower(layout.column_names[c]) == wanted) spec.index = c;
          }
          if (spec.index < 0) {
            for (int c = 0; c < static_cast<int>(layout.column_names.size()); ++c) {
              if (NormaliseName(layout.column_names[c]) == NormaliseName(spec.name)) {
                spec.index = c;
              }
            }
          }
          if (spec.index < 0) {
            throw Error(
                fmt::format("--columns: {}={}: the header (line {}) has no column '{}'; "
                            "its columns are: {}",
                            kRoleKeys[spec.role],
                            spec.name,
                            layout.header_line,
                            spec.name,
                            fmt::join(layout.column_names, ", ")));
          }
        }
        column[spec.role] = spec.index;
      }
      if (column[kTime] < 0 && sample_index_column >= 0) {
        column[kTime] = sample_index_column;
        layout.time_column = sample_index_column;
        if (options.time_unit == TimeUnit::kAuto)
          options.time_unit = TimeUnit::kSampleIndex;
        if (options.time_unit == TimeUnit::kSampleIndex && options.rate_hz <= 0.0) {
          throw Error(
              fmt::format("'{}': column '{}' counts samples rather than time: give the "
                          "sample rate with "
                          "--rate HZ (or --time-unit s if it holds seconds)",
                          source,
                          layout.column_names[sample_index_column]));
        }
      }
      if (column[kAx] < 0 && column[kAy] < 0 && column[kAz] < 0) {
        throw Error(fmt::format(
            "{}:{}: the header names no accelerometer columns (found: {}); expected "
            "ax/acc_x/"
            "accel_x/accX (and y, z), or say which columns they are with --columns "
            "t=NAME,ax=NAME,ay=NAME,az=NAME",
            source,
            layout.header_line,
            fmt::join(layout.column_names, ", ")));
      }
    } else {
      bool mapped = false;
      for (const auto& spec : specs) {
        if (spec.index < 0) {
          throw Error(
              fmt::format("--columns: {}={}: the log '{}' has no header line naming its "
                          "columns; give "
                          "0-based column indices instead (e.g. {}=1)",
                          kRoleKeys[spec.role],
                          spec.name,
                          source,
                          kRoleKeys[spec.role]));
        }
        column[spec.role] = spec.index;
        mapped = true;
      }
      if (!mapped) {
        if (data_columns == 3 && options.rate_hz > 0.0) {
          column[kAx] = 0;
          column[kAy] = 1;
          column[kAz] = 2;
        } else {
          column[kTime] = 0;
          column[kAx] = 1;
          column[kAy] = 2;
          column[kAz] = 3;
        }
      }
    }
    for (int r = kAx; r <= kAz; ++r) {
      if (column[r] < 0) {
        throw Error(fmt::format(
            "'{}': no column for {}{}; name it with --columns {}=NAME|INDEX",
            source,
            kRoleKeys[r],
            header ? fmt::format(" in the header (line {})", layout.header_line) : "",
            kRoleKeys[r]));
      }
    }
    const int gyros = (column[kGx] >= 0) + (column[kGy] >= 0) + (column[kGz] >= 0);
    if (gyros != 0 && gyros != 3) {
      throw Error(
          fmt::format("'{}': found {} of the 3 gyroscope columns; give all of gx, gy, gz "
                      "with --columns",
                      source,
                      gyros));
    }
    for (int r = kTime; r <= kGz; ++r) {
      for (int q = r + 1; q <= kGz; ++q) {
        if (column[r] >= 0 && column[r] == column[q]) {
          throw Error(fmt::format("'{}': {} and {} are both column index {}",
                                  source,
                                  kRoleKeys[r],
                                  kRoleKeys[q],
                                  column[r]));
        }
      }
    }
    layout.time_column = column[kTime];
    for (int i = 0; i < 3; ++i) {
      layout.accel_columns[i] = column[kAx + i];
      layout.gyro_columns[i] = column[kGx + i];
    }
    int max_column = 0;
    for (int r = kTime; r <= kGz; ++r) {
      if (r >= kGx && !parse_gyro) continue;
      max_column = std::max(max_column, column[r]);
    }
    layout.min_columns = max_column + 1;
    if (layout.time_column < 0 && options.rate_hz <= 0.0) {
      throw Error(fmt::format(
          "'{}': no time column{}: give it with --columns t=NAME|INDEX, or the sample "
          "rate "
          "with --rate HZ",
          source,
          header ? fmt::format(" in the header (line {})", layout.header_line) : ""));
    }
    (void)data_columns;
  }

  void ResolveTimeUnit(const std::vector<std::string_view>& time_fields) {
    TimeUnit unit = options.time_unit;
    if (layout.time_column < 0) unit = TimeUnit::kSampleIndex;
    // A unit in the column's name (`millis`, `Time (s)`) is the logger's word.
    if (unit == TimeUnit::kAuto && layout.header_line > 0 &&
        layout.time_column < static_cast<int>(layout.column_names.size())) {
      if (const auto named = TimeUnitOfName(layout.column_names[layout.time_column])) {
        unit = *named;
      }
    }
    if (unit == TimeUnit::kAuto) {
      bool integers = !time_fields.empty();
      for (auto f : time_fields) integers = integers && LooksLikeInteger(f);
      unit = TimeUnit::kSeconds;
      if (integers) {
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
        if (!diffs.empty()) {
          std::nth_element(diffs.begin(), diffs.begin() + diffs.size() / 2, diffs.end());
          const double spacing = diffs[diffs.size() / 2];
          const bool steps_by_one =
              std::all_of(diffs.begin(), diffs.end(), [](double d) { return d == 1.0; });
          if (spacing == 1.0 && options.rate_hz > 0.0) {
            unit = TimeUnit::kSampleIndex;
          } else if (steps_by_one && diffs.size() >= 8) {
            // 0, 1, 2, ... is a sample counter (an ADXL345 sketch's `n`), not
            // milliseconds: read as ms it would blame the hold times.
            throw Error(fmt::format(
                "'{}': column '{}' steps by exactly 1 on every row: it is a sample "
                "index, "
                "not a time; give the sample rate in Hz (or its time unit, if it holds "
                "milliseconds at 1 kHz)",
                source,
                layout.column_names[layout.time_column]));
          } else {
            // The unit that makes the sample period most like an IMU's (10 ms,
            // on a log scale), among periods from 50 µs to 2 s.
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
              }
            }
            if (unit != TimeUnit::kSeconds) {
              const double seconds = unit == TimeUnit::kNanoseconds    ? 1e-9
                                     : unit == TimeUnit::kMicroseconds ? 1e-6
                                                                       : 1e-3;
              warnings.push_back(
                  fmt::format("integer timestamps in '{}' taken as {} (typical spacing "
                              "{:g}, i.e. {:.4g} "
                              "Hz); give --time-unit if that is wrong",
                              layout.column_names[layout.time_column],
                              ToString(unit),
                              spacing,
                              1.0 / (spacing * seconds)));
            }
          }
        }
      }
    }
    layout.time_unit = unit;
    switch (unit) {
      case TimeUnit::kSampleIndex:
        if (options.rate_hz <= 0.0) {
          throw Error(
              fmt::format("'{}': the time column is a sample index: give the sample rate "
                          "with --rate HZ",
                          source));
        }
        layout.seconds_per_time_unit = 1.0 / options.rate_hz;
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

  std::string ColumnLabel(int column) const {
    const std::string name =
        column < static_cast<int>(layout.column_names.size()) && layout.header_line > 0
            ? layout.column_names[column]
            : std::string(
                  kRoleKeys[column < static_cast<int>(roles.size()) ? roles[column]
                                                                    : kNone]);
    return fmt::format("column '{}' (index {})", name, column);
  }

  // Why a data line did not parse; the message is only built then (Problem).
  // Kept by the caller, so that ReadLog's two threads can parse at once.
  enum class Failure { kTooFew, kBadNumber, kNonFinite, kImpossible };
  struct LineFailure {
    Failure kind = Failure::kTooFew;
    int column = 0;
    const char* at = nullptr;
    const char* end = nullptr;
  };
  LineFailure failure;  // LogScanner's

  static bool Fail(LineFailure* why,
                   Failure kind,
                   int column,
                   const char* at,
                   const char* end_of_number = nullptr) {
    *why = {kind, column, at, end_of_number};
    return false;
  }

  std::string Problem(std::string_view text, const LineFailure& why) const {
    switch (why.kind) {
      case Failure::kTooFew:
        return TooFew(text, why.column);
      case Failure::kBadNumber:
        return BadNumber(text, why.column, why.at);
      case Failure::kNonFinite:
        return fmt::format("non-finite value '{}' in {}; remove or fix the line",
                           std::string_view(why.at, why.end - why.at),
                           ColumnLabel(why.column));
      case Failure::kImpossible:
        return fmt::format(
            "reading '{}' in {} is beyond any accelerometer's range (±{:g} {}, {:g} g): "
            "a "
            "corrupt line, or readings in other units",
            std::string_view(why.at, why.end - why.at),
            ColumnLabel(why.column),
            MaxReading(options.units),
            ToString(options.units),
            kMaxReadingG);
    }
    return "";
  }

  // Parses one data line; false when malformed (then Problem says why). The
  // hot path: no allocation, one pass, fast_float for the numbers.
  bool ParseData(std::string_view text, LogLine* out, LineFailure* why) const {
    const char* const line_begin = text.data();
    const char* p = line_begin;
    const char* const stop = line_begin + text.size();
    const char delimiter = layout.delimiter;
    for (int column = 0; column <= last_needed; ++column) {
      // Find the field start.
      if (delimiter == ' ') {
        while (p < stop && IsBlank(*p)) ++p;
        if (p == stop) return Fail(why, Failure::kTooFew, column, p);
      } else if (column > 0) {
        if (p == stop) return Fail(why, Failure::kTooFew, column, p);
        ++p;  // the delimiter
      }
      const Role role = roles[column];
      if (role == kNone) {
        if (delimiter == ' ') {
          while (p < stop && !IsBlank(*p)) ++p;
        } else {
          const auto* d = static_cast<const char*>(std::memchr(p, delimiter, stop - p));
          p = d ? d : stop;
        }
        continue;
      }
      if (delimiter != ' ') {
        while (p < stop && IsBlank(*p)) ++p;
      }
      // Spreadsheets and some loggers quote every field: "0.981".
      const char* field_begin = p;
      const char quote = p < stop && (*p == '"' || *p == '\'') ? *p : '\0';
      if (quote != '\0') ++p;
      const char* number_begin = p;
      if (p < stop && *p == '+') ++p;
      double value = 0.0;
      const auto result = fast_float::from_chars_advanced(p, stop, value, number_format);
      const char* after = result.ptr;
      const char* field_end = after;
      if (quote != '\0') {
        if (after == stop || *after != quote) {
          return Fail(why, Failure::kBadNumber, column, field_begin);
        }
        ++field_end;
      }
      const bool at_end = field_end == stop || IsBlank(*field_end) ||
                          (delimiter != ' ' && *field_end == delimiter);
      if (result.ec != std::errc() || !at_end || (p != number_begin && *p == '-')) {
        return Fail(why, Failure::kBadNumber, column, field_begin);
      }
      if (!std::isfinite(value)) {
        return Fail(why, Failure::kNonFinite, column, number_begin, after);
      }
      // One row of 1e308 would poison detection's threshold (or 1e20 its
      // statistics): a reading no accelerometer can give is refused here.
      if (role >= kAx && role <= kAz && std::abs(value) > max_reading) {
        return Fail(why, Failure::kImpossible, column, number_begin, after);
      }
      p = field_end;
      if (delimiter != ' ') {
        while (p < stop && IsBlank(*p)) ++p;
        if (p != stop && *p != delimiter) {
          return Fail(why, Failure::kBadNumber, column, field_begin);
        }
      }
      switch (role) {
        case kTime:
          out->time_raw = value;
          break;
        case kAx:
        case kAy:
        case kAz:
          out->accel[role - kAx] = value;
          out->accel_span[role - kAx] = {
              static_cast<std::uint32_t>(number_begin - line_begin),
              static_cast<std::uint32_t>(after - line_begin)};
          break;
        default:
          out->gyro[role - kGx] = value;
          out->gyro_span[role - kGx] = {
              static_cast<std::uint32_t>(number_begin - line_begin),
              static_cast<std::uint32_t>(after - line_begin)};
          break;
      }
    }
    return true;
  }

  std::string TooFew(std::string_view text, int found) const {
    return fmt::format(
        "expected at least {} columns separated by {} ({}), found {}: '{}'",
        layout.min_columns,
        DelimiterName(layout.delimiter),
        layout.Describe(),
        found,
        Printable(text, 80));
  }

  std::string BadNumber(std::string_view text,
                        int column,
                        const char* field_begin) const {
    const char* const stop = text.data() + text.size();
    const char* e = field_begin;
    while (e < stop && !(layout.delimiter == ' ' ? IsBlank(*e) : *e == layout.delimiter))
      ++e;
    const std::string_view field = Trim(std::string_view(field_begin, e - field_begin));
    if (field.empty())
      return fmt::format("{} is empty; expected a number", ColumnLabel(column));
    return fmt::format(
        "expected a number in {}, found '{}'", ColumnLabel(column), Printable(field));
  }
};

}  // namespace

struct LogScanner::Impl : ScannerState {};

LogScanner::LogScanner(const std::string& path,
                       const LogOptions& options,
                       bool parse_gyro)
    : impl_(std::make_unique<Impl>()) {
  const std::string problem = options.Validate();
  if (!problem.empty()) throw Error("log options: " + problem);
  impl_->options = options;
  impl_->max_reading = MaxReading(options.units);
  impl_->Open(path);
  impl_->Detect(parse_gyro);
}

LogScanner::~LogScanner() = default;

const LogLayout& LogScanner::layout() const { return impl_->layout; }
const std::string& LogScanner::source() const { return impl_->source; }
const std::vector<std::string>& LogScanner::warnings() const { return impl_->warnings; }
std::uint64_t LogScanner::bytes_read() const { return impl_->consumed; }
std::uint64_t LogScanner::total_bytes() const { return impl_->total; }

bool LogScanner::Next(LogLine* line) {
  Impl& s = *impl_;
  std::string pending;  // a malformed line, fatal unless nothing follows it
  std::size_t pending_line = 0;
  std::string_view text;
  std::string_view eol;
  while (s.GetLine(&text, &eol)) {
    const bool other = s.line_number == s.layout.header_line ||
                       s.line_number <= s.skipped_lines || Impl::IsCommentOrBlank(text);
    if (!pending.empty()) {
      if (other && Trim(text).empty()) continue;
      throw Error(fmt::format("{}:{}: {}", s.source, pending_line, pending));
    }
    line->text = text;
    line->eol = eol;
    line->line_number = s.line_number;
    line->is_data = !other;
    if (other) return true;
    if (s.layout.time_column < 0) line->time_raw = static_cast<double>(s.data_rows);
    if (s.ParseData(text, line, &s.failure)) {
      ++s.data_rows;
      return true;
    }
    pending = s.Problem(text, s.failure);
    pending_line = s.line_number;
  }
  if (!pending.empty()) {
    s.warnings.push_back(
        fmt::format("{}:{}: last line is incomplete ({}); ignored, as when a logger is "
                    "cut off mid-write",
                    s.source,
                    pending_line,
                    pending));
  }
  return false;
}

namespace {

// ReadLog's parser of a data line when the delimiter is one character: plain
// fields straight to fast_float, and false for anything else (blanks or a '+'
// before a number, a blank after it, too few fields, a bad or non-finite
// value), which ParseData then parses: the same values, and its message.
// ParseData's generality cost a CSV log a fifth more time than fast_float.
bool ParsePlainRow(const ScannerState& s, std::string_view text, LogLine* out) {
  const char* p = text.data();
  const char* const stop = p + text.size();
  const char delimiter = s.layout.delimiter;
  const Role* const roles = s.roles.data();
  for (int column = 0; column <= s.last_needed; ++column) {
    if (column > 0) {
      if (p == stop) return false;
      ++p;  // the delimiter (where the previous field stopped)
    }
    const Role role = roles[column];
    if (role == kNone) {
      const auto* d = static_cast<const char*>(std::memchr(p, delimiter, stop - p));
      p = d ? d : stop;
      continue;
    }
    if (p == stop || IsBlank(*p) || *p == '+') return false;
    double value = 0.0;
    const auto result = fast_float::from_chars_advanced(p, stop, value, s.number_format);
    if (result.ec != std::errc() || (result.ptr != stop && *result.ptr != delimiter) ||
        !std::isfinite(value) ||
        (role >= kAx && role <= kAz && std::abs(value) > s.max_reading)) {
      return false;
    }
    p = result.ptr;
    if (role == kTime) {
      out->time_raw = value;
    } else if (role <= kAz) {
      out->accel[role - kAx] = value;
    } else {
      out->gyro[role - kGx] = value;
    }
  }
  return true;
}

// ReadLog is bound by turning text into numbers, so it parses on two cores:
// the input is cut into chunks of whole lines, read in file order by
// whichever thread is free; each is parsed into its own rows; the calling
// thread merges the parsed chunks in file order into the Recording, with the
// checks LogScanner + the loop over its lines made (line numbers, the first
// error in file order, a malformed last line, duplicates, time going back),
// and the same messages. Memory: kChunksInFlight chunks at most.
constexpr std::size_t kPipelineChunkBytes = std::size_t{1} << 20;
constexpr std::size_t kChunksInFlight = 4;

struct Chunk {
  enum class State { kFree, kBusy, kParsed };
  State state = State::kFree;
  std::size_t sequence = 0;
  // Whole lines (the input's last line may lack its end); `size` bytes used.
  std::unique_ptr<char[]> bytes;
  std::size_t capacity = 0;
  std::size_t size = 0;
  // Reading stopped here: a read error, or a line with no end in sight.
  std::string read_error;
  bool line_too_long = false;

  // Parsed: one entry per data line before the first malformed one. `time`
  // is in seconds, or the chunk's own row index when the log has no time
  // column (the merge knows the rows before it).
  std::vector<double> time;
  std::vector<Eigen::Vector3d> accel;
  std::vector<Eigen::Vector3d> gyro;
  std::size_t lines = 0;          // lines in the chunk
  std::size_t last_row_line = 0;  // 1-based within the chunk
  std::size_t first_row_bytes = 0;
  bool has_content = false;      // a line that is not blank (ends a pending failure)
  std::size_t failure_line = 0;  // first malformed data line, 0 for none
  std::string failure;
  bool failure_fatal = false;  // something but blank lines follows it
  std::exception_ptr error;    // from parsing (out of memory)
};

class ChunkPipeline {
 public:
  ChunkPipeline(ScannerState& s, double time_scale, double gyro_scale)
      : s_(s),
        time_scale_(time_scale),
        gyro_scale_(gyro_scale),
        index_time_(s.layout.time_column < 0),
        gyro_(s.layout.has_gyro()) {
    // The first chunk starts with what the layout was found from.
    carry_.assign(s.buf.data() + s.begin, s.buf.data() + s.end);
    consumed_ = s.begin;
    std::vector<char>().swap(s.buf);
    s.begin = s.end = 0;
  }

  ~ChunkPipeline() { StopHelper(); }

  void StartHelper() {
    try {
      helper_ = std::thread([this] {
        while (Chunk* c = Claim(/*wait=*/true)) Parse(c);
      });
    } catch (const std::system_error&) {
      // No second thread: the calling thread does it all.
    }
  }

  void StopHelper() {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
    }
    ready_.notify_all();
    if (helper_.joinable()) helper_.join();
  }

  // The next chunk in file order once parsed; nullptr after the last. The
  // calling thread reads and parses chunks too while it waits.
  Chunk* NextParsed() {
    while (true) {
      {
        std::unique_lock lock(mutex_);
        Chunk& next = slots_[merged_ % kChunksInFlight];
        if (next.state == Chunk::State::kParsed && next.sequence == merged_) return &next;
        if (input_done_ && merged_ == claimed_) return nullptr;
      }
      if (Chunk* c = Claim(/*wait=*/false)) {
        Parse(c);
        continue;
      }
      std::unique_lock lock(mutex_);
      ready_.wait(lock, [&] {
        const Chunk& next = slots_[merged_ % kChunksInFlight];
        return (next.state == Chunk::State::kParsed && next.sequence == merged_) ||
               (input_done_ && merged_ == claimed_) ||
               (!helper_.joinable() && !input_done_);
      });
    }
  }

  void Release(Chunk* c) {
    consumed_ += c->size;
    {
      std::lock_guard lock(mutex_);
      c->state = Chunk::State::kFree;
      ++merged_;
    }
    ready_.notify_all();
  }

  // Bytes of the input merged so far.
  std::uint64_t consumed() const { return consumed_; }
  std::size_t HeaderLineOf(const Chunk& c) const {
    return c.sequence == 0 && s_.layout.header_line > 0
               ? s_.layout.header_line - s_.skipped_lines
               : 0;
  }

 private:
  // Claims the next chunk in file order and reads it; nullptr when the input
  // has ended, or when there is no free slot and `wait` is false.
  Chunk* Claim(bool wait) {
    std::unique_lock read_lock(read_mutex_, std::defer_lock);
    if (wait) {
      read_lock.lock();
    } else if (!read_lock.try_lock()) {
      return nullptr;
    }
    Chunk* c = nullptr;
    {
      std::unique_lock lock(mutex_);
      auto free = [&] {
        return slots_[claimed_ % kChunksInFlight].state == Chunk::State::kFree;
      };
      if (wait) ready_.wait(lock, [&] { return stop_ || input_done_ || free(); });
      if (stop_ || input_done_ || !free()) return nullptr;
      c = &slots_[claimed_ % kChunksInFlight];
      c->state = Chunk::State::kBusy;
      c->sequence = claimed_;
    }
    bool got = true;
    c->error = nullptr;
    try {
      got = Read(c);
    } catch (...) {  // out of memory: reported when this chunk's turn comes
      c->error = std::current_exception();
      c->size = 0;
    }
    std::lock_guard lock(mutex_);
    if (!got) {
      c->state = Chunk::State::kFree;
      input_done_ = true;
      ready_.notify_all();
      return nullptr;
    }
    ++claimed_;
    if (!c->read_error.empty() || c->line_too_long || c->error) input_done_ = true;
    return c;
  }

  // Fills `c` with the carried-over bytes and whole lines read after them,
  // about kPipelineChunkBytes; false when the input has ended.
  bool Read(Chunk* c) {
    c->read_error.clear();
    c->line_too_long = false;
    std::size_t size = carry_.size();
    std::size_t want = std::max(kPipelineChunkBytes, size);
    Reserve(c, want, 0);
    std::memcpy(c->bytes.get(), carry_.data(), size);
    carry_.clear();
    while (true) {
      while (!s_.eof && size < want) {
        const ssize_t n = ::read(s_.fd, c->bytes.get() + size, want - size);
        if (n < 0) {
          if (errno == EINTR) continue;
          c->read_error =
              fmt::format("error reading '{}': {}", s_.source, std::strerror(errno));
          break;
        }
        if (n == 0) {
          s_.eof = true;
          break;
        }
        size += static_cast<std::size_t>(n);
      }
      if (size == 0 && c->read_error.empty()) return false;
      if (s_.eof && c->read_error.empty()) break;  // the rest of the input
      // Cut after the last line end; the rest begins the next chunk. (A
      // read error comes after the whole lines before it.)
      const char* const data = c->bytes.get();
      const auto* nl = static_cast<const char*>(::memrchr(data, '\n', size));
      if (nl != nullptr) {
        const std::size_t cut = static_cast<std::size_t>(nl - data) + 1;
        if (c->read_error.empty()) carry_.assign(data + cut, data + size);
        size = cut;
        break;
      }
      if (!c->read_error.empty()) {
        size = 0;
        break;
      }
      // One line so far, from the chunk's start (the carry starts a line).
      if (size >= kMaxLineBytes) {
        c->line_too_long = true;
        size = 0;
        break;
      }
      want = size + kPipelineChunkBytes;
      Reserve(c, want, size);
    }
    c->size = size;
    return true;
  }

  // Room for `bytes` in `c`, keeping its first `keep` bytes.
  static void Reserve(Chunk* c, std::size_t bytes, std::size_t keep) {
    if (c->capacity >= bytes) return;
    auto grown = std::make_unique_for_overwrite<char[]>(bytes);
    if (keep > 0) std::memcpy(grown.get(), c->bytes.get(), keep);
    c->bytes = std::move(grown);
    c->capacity = bytes;
  }

  void Parse(Chunk* c) {
    try {
      if (!c->error) ParseLines(c);
    } catch (...) {
      c->error = std::current_exception();
    }
    {
      std::lock_guard lock(mutex_);
      c->state = Chunk::State::kParsed;
    }
    ready_.notify_all();
  }

  // LogScanner::Next over a chunk, keeping the rows.
  void ParseLines(Chunk* c) const {
    c->time.clear();
    c->accel.clear();
    c->gyro.clear();
    c->lines = 0;
    c->last_row_line = 0;
    c->first_row_bytes = 0;
    c->has_content = false;
    c->failure_line = 0;
    c->failure.clear();
    c->failure_fatal = false;
    const std::size_t header_line = HeaderLineOf(*c);
    const char* p = c->bytes.get();
    const char* const end = p + c->size;
    std::size_t line = 0;
    LogLine row;
    ScannerState::LineFailure why;
    const bool plain = s_.layout.delimiter != ' ';
    while (p < end) {
      const auto* nl = static_cast<const char*>(std::memchr(p, '\n', end - p));
      const char* const stop = nl ? nl : end;
      std::string_view text(p, static_cast<std::size_t>(stop - p));
      if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
      const char* const line_begin = p;
      p = nl ? nl + 1 : end;
      ++line;
      if (c->failure_line > 0) {
        if (Trim(text).empty()) continue;
        c->failure_fatal = true;
        break;
      }
      if (!c->has_content) c->has_content = !Trim(text).empty();
      if (line == header_line || ScannerState::IsCommentOrBlank(text)) continue;
      if (index_time_) row.time_raw = static_cast<double>(c->time.size());
      if (!(plain && ParsePlainRow(s_, text, &row)) && !s_.ParseData(text, &row, &why)) {
        c->failure_line = line;
        c->failure = s_.Problem(text, why);
        continue;
      }
      if (c->time.empty()) c->first_row_bytes = static_cast<std::size_t>(p - line_begin);
      c->time.push_back(index_time_ ? row.time_raw : row.time_raw * time_scale_);
      c->accel.push_back(row.accel);
      if (gyro_) c->gyro.push_back(row.gyro * gyro_scale_);
      c->last_row_line = line;
    }
    // Lines after a fatal failure are not needed (the merge stops there).
    c->lines = line;
  }

  ScannerState& s_;
  const double time_scale_;
  const double gyro_scale_;
  const bool index_time_;
  const bool gyro_;
  std::thread helper_;

  std::mutex read_mutex_;  // reading: one thread at a time, in file order
  std::vector<char> carry_;
  std::uint64_t consumed_ = 0;  // the merging thread's

  std::mutex mutex_;
  std::condition_variable ready_;
  std::array<Chunk, kChunksInFlight> slots_;
  std::size_t claimed_ = 0;  // chunks read
  std::size_t merged_ = 0;
  bool input_done_ = false;
  bool stop_ = false;
};

// A logger's timestamp that is a 16- or 32-bit counter wraps around to 0:
// when time goes back from just below 2^N of its units, say so.
std::string CounterWrapHint(double raw_time_before) {
  for (const int bits : {16, 32}) {
    const double wrap = std::ldexp(1.0, bits);
    if (raw_time_before > 0.99 * wrap && raw_time_before < wrap) {
      return fmt::format(
          " (the timestamp looks like a {}-bit counter that wrapped around at {:.0f}: "
          "unwrap "
          "it, or leave time out of --columns and give --rate HZ)",
          bits,
          wrap);
    }
  }
  return "";
}

// 1-based line (within the chunk) of the chunk's `row`th stored row: only
// needed for messages, so found again by walking the lines.
std::size_t LineOfRow(const Chunk& c, std::size_t row, std::size_t header_line) {
  const char* p = c.bytes.get();
  const char* const end = p + c.size;
  std::size_t line = 0;
  std::size_t rows = 0;
  while (p < end) {
    const auto* nl = static_cast<const char*>(std::memchr(p, '\n', end - p));
    const char* const stop = nl ? nl : end;
    std::string_view text(p, static_cast<std::size_t>(stop - p));
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    p = nl ? nl + 1 : end;
    ++line;
    if (line == header_line || ScannerState::IsCommentOrBlank(text)) continue;
    if (rows++ == row) return line;
  }
  return line;
}

}  // namespace

Recording ReadLog(const std::string& path, const LogOptions& options) {
  const std::string problem = options.Validate();
  if (!problem.empty()) throw Error("log options: " + problem);
  ScannerState s;
  s.options = options;
  s.max_reading = MaxReading(options.units);
  s.Open(path);
  s.Detect(/*parse_gyro=*/true);
  const LogLayout& layout = s.layout;

  Recording rec;
  rec.units = options.units;
  rec.source = s.source;
  const bool gyro = layout.has_gyro();
  const bool index_time = layout.time_column < 0;
  const double gyro_scale =
      options.gyro_in_dps && !options.gyro_in_counts ? std::numbers::pi / 180.0 : 1.0;
  if (options.gyro_in_counts) rec.gyro_units = GyroUnits::kCounts;
  const double time_scale = layout.seconds_per_time_unit;

  if (s.skipped_bytes > s.begin) {
    s.consumed += s.skipped_bytes - s.begin;
    s.begin = s.skipped_bytes;
  }
  ChunkPipeline pipeline(s, time_scale, gyro_scale);
  pipeline.StartHelper();

  std::size_t line_base = s.skipped_lines;  // lines before the chunk being merged
  std::size_t rows_before = 0;
  std::size_t duplicates = 0;
  std::size_t first_duplicate_line = 0;
  std::size_t previous_line = 0;  // of the last row kept
  std::size_t pending_line = 0;   // a malformed line, fatal unless nothing follows it
  std::string pending;
  bool reserved = false;
  while (Chunk* c = pipeline.NextParsed()) {
    const std::size_t header_line = pipeline.HeaderLineOf(*c);
    if (c->error) std::rethrow_exception(c->error);
    if (pending.empty() || !c->has_content) {
      const std::size_t rows = c->time.size();
      if (index_time) {
        for (std::size_t j = 0; j < rows; ++j) {
          c->time[j] = static_cast<double>(rows_before + j) * time_scale;
        }
      }
      if (!reserved && rows > 0 && s.total > 0) {
        // Size the arrays once, from the first line's length (or the
        // chunk's average, if shorter), so that a long log does not pay for
        // repeated doubling (and twice the memory).
        const double bytes_per_row = std::min(static_cast<double>(c->first_row_bytes),
                                              static_cast<double>(c->size) / rows);
        const auto estimate = static_cast<std::size_t>(
            1.1 * static_cast<double>(s.total) / std::max(bytes_per_row, 8.0));
        rec.time_s.reserve(estimate);
        rec.accel.reserve(estimate);
        if (gyro) rec.gyro_radps.reserve(estimate);
        reserved = true;
      }
      // The file's line number of a row of this chunk.
      auto line_of = [&](std::size_t row) {
        return line_base +
               (row + 1 == rows ? c->last_row_line : LineOfRow(*c, row, header_line));
      };
      std::size_t j = 0;
      std::size_t last_kept = rows;  // none yet in this chunk
      while (j < rows) {
        // A run of rows each later than the one before: copied at once.
        std::size_t k = j;
        double previous = 0.0;
        if (rec.time_s.empty()) {
          previous = c->time[k++];  // the first row has nothing to follow
        } else {
          previous = rec.time_s.back();
        }
        while (k < rows && c->time[k] > previous) previous = c->time[k++];
        if (k > j) {
          rec.time_s.insert(rec.time_s.end(), c->time.begin() + j, c->time.begin() + k);
          rec.accel.insert(rec.accel.end(), c->accel.begin() + j, c->accel.begin() + k);
          if (gyro) {
            rec.gyro_radps.insert(
                rec.gyro_radps.end(), c->gyro.begin() + j, c->gyro.begin() + k);
          }
          last_kept = k - 1;
        }
        if (k == rows) break;
        const double t = c->time[k];
        const double before = rec.time_s.back();
        if (t == before) {
          if (duplicates++ == 0) first_duplicate_line = line_of(k);
          j = k + 1;
          continue;
        }
        if (last_kept < rows) previous_line = line_of(last_kept);
        throw Error(
            fmt::format("{}:{}: time goes back: {:.9g} s after {:.9g} s on line {}; the "
                        "rows must be in "
                        "time order{}",
                        rec.source,
                        line_of(k),
                        t,
                        before,
                        previous_line,
                        CounterWrapHint(before / time_scale)));
      }
      if (last_kept < rows) previous_line = line_of(last_kept);
      rows_before += rows;
      if (c->failure_line > 0) {
        if (c->failure_fatal) {
          throw Error(fmt::format(
              "{}:{}: {}", rec.source, line_base + c->failure_line, c->failure));
        }
        pending_line = line_base + c->failure_line;
        pending = c->failure;
      }
    } else {
      throw Error(fmt::format("{}:{}: {}", rec.source, pending_line, pending));
    }
    line_base += c->lines;
    if (c->line_too_long) {
      throw Error(fmt::format(
          "{}:{}: line longer than {} KiB: this does not look like a text log",
          rec.source,
          line_base + 1,
          kMaxLineBytes / 1024));
    }
    if (!c->read_error.empty()) throw Error(c->read_error);
    pipeline.Release(c);
    if (s.options.progress && s.total > 0) {
      const double fraction = std::min(
          1.0, static_cast<double>(pipeline.consumed()) / static_cast<double>(s.total));
      if (fraction - s.last_progress >= 0.01) {
        s.last_progress = fraction;
        s.options.progress(fraction);
      }
    }
  }
  pipeline.StopHelper();
  if (s.options.progress && s.total > 0 && s.last_progress < 1.0) s.options.progress(1.0);

  rec.warnings = s.warnings;
  if (!pending.empty()) {
    rec.warnings.push_back(
        fmt::format("{}:{}: last line is incomplete ({}); ignored, as when a logger is "
                    "cut off mid-write",
                    rec.source,
                    pending_line,
                    pending));
  }
  if (rec.empty()) {
    throw Error(fmt::format("'{}' has no data rows{}",
                            rec.source,
                            layout.header_line > 0 ? " after its header" : ""));
  }
  // Rows are in time order: the first and last times bound them all.
  for (const double t : {rec.time_s.front(), rec.time_s.back()}) {
    if (std::abs(t) > kMaxTimeS) {
      throw Error(fmt::format(
          "{}: a time of {:.6g} s is beyond any logger's clock (more than {:g} s, 31,700 "
          "years): the time column is not a time in the unit it is read in",
          rec.source,
          t,
          kMaxTimeS));
    }
  }
  if (duplicates > 0) {
    rec.warnings.push_back(
        fmt::format("{}: {} row{} with a duplicated timestamp dropped (first on line {})",
                    rec.source,
                    duplicates,
                    duplicates == 1 ? "" : "s",
                    first_duplicate_line));
  }
  // Gaps: steps much longer than the typical one (from up to 10,000 steps
  // spread over the log, so that this stays cheap).
  if (rec.size() >= 3) {
    const std::size_t n = rec.size() - 1;
    const std::size_t stride = std::max<std::size_t>(1, n / 10000);
    std::vector<double> steps;
    for (std::size_t i = 0; i < n; i += stride)
      steps.push_back(rec.time_s[i + 1] - rec.time_s[i]);
    std::nth_element(steps.begin(), steps.begin() + steps.size() / 2, steps.end());
    const double typical = steps[steps.size() / 2];
    const double limit = 5.0 * typical;
    std::size_t gaps = 0;
    double largest = 0.0;
    double largest_at = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      const double step = rec.time_s[i + 1] - rec.time_s[i];
      if (step > limit) {
        ++gaps;
        if (step > largest) {
          largest = step;
          largest_at = rec.time_s[i];
        }
      }
    }
    if (gaps > 0) {
      rec.warnings.push_back(
          fmt::format("{}: {} gap{} in time longer than 5 sample periods ({:.4g} s); the "
                      "largest is {:.4g} "
                      "s after t = {:.9g} s",
                      rec.source,
                      gaps,
                      gaps == 1 ? "" : "s",
                      typical,
                      largest,
                      largest_at));
    }
  }
  return rec;
}

}  // namespace mpcal
