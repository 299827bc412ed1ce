#include "log_columns.h"

#include <algorithm>
#include <array>
#include <map>
#include <system_error>

#include <fast_float/fast_float.h>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "mpcal/error.h"

namespace mpcal::logio {
namespace {

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

}  // namespace

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

namespace {

using ColumnOfRole = std::array<int, 8>;

// What a log's columns are called and which option maps them: a log's
// (ax, ay, az, and gx, gy, gz), or a gyroscope's own log, whose three reading
// columns take the accelerometer's places (kAx...) under the names gx, gy, gz.
struct Naming {
  const char* const* keys;
  Option option;
  Role (*role_of)(std::string_view name);
  bool gyroscope_only;
};

constexpr const char* kGyroLogKeys[] = {"", "t", "gx", "gy", "gz", "", "", ""};

// A gyroscope log's header: gx/gyr_x/gyro_x as in any log, and the bare axis
// names gyroscope loggers use alone (x, wx, omega_x, rate_x).
Role GyroLogRoleOfName(std::string_view name) {
  const Role r = RoleOfName(name);
  if (r >= kGx && r <= kGz) return static_cast<Role>(kAx + (r - kGx));
  if (r != kTime) {
    const std::string n = NormaliseName(name);
    const char* axes = "xyz";
    for (int i = 0; i < 3; ++i) {
      for (std::string prefix :
           {"", "w", "omega", "rate", "angularrate", "angularvelocity"}) {
        if (n == prefix + axes[i]) return static_cast<Role>(kAx + i);
      }
    }
    return kNone;
  }
  return r;
}

const Naming kLogNaming{kRoleKeys, Option::kLogColumns, &RoleOfName, false};
const Naming kGyroLogNaming{
    kGyroLogKeys, Option::kGyroLogColumns, &GyroLogRoleOfName, true};

std::string InHeader(const LogLayout& layout) {
  return layout.header_line > 0
             ? fmt::format(" in the header (line {})", layout.header_line)
             : "";
}

// The index of the header column `spec` names: exact (any case) first, then
// as RoleOfName compares names.
int ColumnNamed(const LogLayout& layout, const ColumnSpec& spec, const Naming& naming) {
  const auto& names = layout.column_names;
  const std::string wanted = Lower(spec.name);
  int index = -1;
  for (int c = 0; c < static_cast<int>(names.size()); ++c) {
    if (Lower(names[c]) == wanted) index = c;
  }
  if (index >= 0) return index;
  for (int c = 0; c < static_cast<int>(names.size()); ++c) {
    if (NormaliseName(names[c]) == NormaliseName(spec.name)) index = c;
  }
  if (index < 0) {
    throw Error(ErrorKind::kColumns,
                fmt::format("columns {}={}: the header (line {}) has no column "
                            "'{}'; its columns are: {}",
                            naming.keys[spec.role],
                            spec.name,
                            layout.header_line,
                            spec.name,
                            fmt::join(names, ", ")),
                Give({{naming.option, ""}}));
  }
  return index;
}

// A header with no accelerometer names: bare axes x, y, z are the
// accelerometer's (Sensor Logger writes `time,seconds_elapsed,z,y,x` in a
// file per sensor, awesome-sensor-logger UNITS.md), and gravity-free
// acceleration (phyphox's "Acceleration without g" exports `Linear
// Acceleration x (m/s^2)`) is refused: the method measures gravity.
void MapBareAxes(const std::string& source,
                 const LogLayout& layout,
                 ColumnOfRole* column) {
  const char* axes = "xyz";
  for (int c = 0; c < static_cast<int>(layout.column_names.size()); ++c) {
    const std::string n = NormaliseName(layout.column_names[c]);
    for (int i = 0; i < 3; ++i) {
      if (n == std::string("linearacceleration") + axes[i]) {
        throw Error(ErrorKind::kInput,
                    fmt::format("{}:{}: column '{}' is acceleration with gravity "
                                "removed; calibration measures gravity, so it needs "
                                "the accelerometer's readings with gravity (phyphox: "
                                "'Acceleration with g')",
                                source,
                                layout.header_line,
                                layout.column_names[c]));
      }
      if (n == std::string(1, axes[i]) && (*column)[kAx + i] < 0) {
        (*column)[kAx + i] = c;
      }
    }
  }
}

// The header's names, then the explicit mapping over them.
void MapFromHeader(const std::string& source,
                   std::vector<ColumnSpec> specs,
                   const Naming& naming,
                   LogOptions* options,
                   LogLayout* layout,
                   ColumnOfRole* column) {
  int sample_index_column = -1;
  for (int c = 0; c < static_cast<int>(layout->column_names.size()); ++c) {
    const Role r = naming.role_of(layout->column_names[c]);
    if (r != kNone && (*column)[r] < 0) (*column)[r] = c;
    if (r == kNone && sample_index_column < 0 &&
        IsSampleIndexName(layout->column_names[c])) {
      sample_index_column = c;
    }
  }
  for (auto& spec : specs) {
    if (spec.index < 0) spec.index = ColumnNamed(*layout, spec, naming);
    (*column)[spec.role] = spec.index;
  }
  if ((*column)[kTime] < 0 && sample_index_column >= 0) {
    (*column)[kTime] = sample_index_column;
    layout->time_column = sample_index_column;
    if (options->time_unit == TimeUnit::kAuto)
      options->time_unit = TimeUnit::kSampleIndex;
    if (options->time_unit == TimeUnit::kSampleIndex && options->rate_hz <= 0.0) {
      throw Error(ErrorKind::kTime,
                  fmt::format("'{}': column '{}' counts samples rather than time, so "
                              "the sample rate is needed (or the time unit, if it holds "
                              "seconds)",
                              source,
                              layout->column_names[sample_index_column]),
                  Give({{Option::kLogRate, ""}, {Option::kLogTimeUnit, "s"}}));
    }
  }
  if ((*column)[kAx] < 0 && (*column)[kAy] < 0 && (*column)[kAz] < 0 &&
      naming.gyroscope_only) {
    throw Error(
        ErrorKind::kColumns,
        fmt::format("{}:{}: the header names no gyroscope columns (found: {}); "
                    "expected gx/gyr_x/wx/x (and y, z), or a mapping of the columns",
                    source,
                    layout->header_line,
                    fmt::join(layout->column_names, ", ")),
        Give({{naming.option, "t=NAME,gx=NAME,gy=NAME,gz=NAME"}}));
  }
  if ((*column)[kAx] < 0 && (*column)[kAy] < 0 && (*column)[kAz] < 0) {
    MapBareAxes(source, *layout, column);
  }
  if ((*column)[kAx] < 0 && (*column)[kAy] < 0 && (*column)[kAz] < 0) {
    throw Error(
        ErrorKind::kColumns,
        fmt::format("{}:{}: the header names no accelerometer columns (found: "
                    "{}); expected ax/acc_x/accel_x/accX (and y, z), or a mapping "
                    "of the columns",
                    source,
                    layout->header_line,
                    fmt::join(layout->column_names, ", ")),
        Give({{Option::kLogColumns, "t=NAME,ax=NAME,ay=NAME,az=NAME"}}));
  }
}

// No header: the mapping's indices, or t, ax, ay, az in order (ax, ay, az
// for three columns and a rate).
void MapWithoutHeader(const std::string& source,
                      const std::vector<ColumnSpec>& specs,
                      std::size_t data_columns,
                      const Naming& naming,
                      const LogOptions& options,
                      ColumnOfRole* column) {
  for (const auto& spec : specs) {
    if (spec.index < 0) {
      throw Error(
          ErrorKind::kColumns,
          fmt::format("columns {}={}: the log '{}' has no header line "
                      "naming its columns, so the mapping needs 0-based column indices",
                      naming.keys[spec.role],
                      spec.name,
                      source),
          Give({{naming.option, fmt::format("{}=1", naming.keys[spec.role])}}));
    }
    (*column)[spec.role] = spec.index;
  }
  if (!specs.empty()) return;
  if (data_columns == 3 && options.rate_hz > 0.0) {
    (*column)[kAx] = 0;
    (*column)[kAy] = 1;
    (*column)[kAz] = 2;
  } else {
    (*column)[kTime] = 0;
    (*column)[kAx] = 1;
    (*column)[kAy] = 2;
    (*column)[kAz] = 3;
  }
}

// Every accelerometer axis, all three gyroscope axes or none, no column
// twice, and a time column or a rate.
void CheckMapping(const std::string& source,
                  const LogLayout& layout,
                  const Naming& naming,
                  const LogOptions& options,
                  const ColumnOfRole& column) {
  for (int r = kAx; r <= kAz; ++r) {
    if (column[r] < 0) {
      throw Error(
          ErrorKind::kColumns,
          fmt::format(
              "'{}': no column for {}{}", source, naming.keys[r], InHeader(layout)),
          Give({{naming.option, fmt::format("{}=NAME|INDEX", naming.keys[r])}}));
    }
  }
  const int gyros = (column[kGx] >= 0) + (column[kGy] >= 0) + (column[kGz] >= 0);
  if (gyros != 0 && gyros != 3) {
    throw Error(
        ErrorKind::kColumns,
        fmt::format("'{}': found {} of the 3 gyroscope columns; all of gx, gy, gz "
                    "are needed",
                    source,
                    gyros),
        Give({{Option::kLogColumns, "gx=NAME,gy=NAME,gz=NAME"}}));
  }
  for (int r = kTime; r <= kGz; ++r) {
    for (int q = r + 1; q <= kGz; ++q) {
      if (column[r] >= 0 && column[r] == column[q]) {
        throw Error(ErrorKind::kColumns,
                    fmt::format("'{}': {} and {} are both column index {}",
                                source,
                                naming.keys[r],
                                naming.keys[q],
                                column[r]));
      }
    }
  }
  if (column[kTime] < 0 && options.rate_hz <= 0.0) {
    throw Error(ErrorKind::kTime,
                fmt::format("'{}': no time column{}", source, InHeader(layout)),
                Give({{naming.option, "t=NAME|INDEX"}, {Option::kLogRate, ""}}));
  }
}

}  // namespace

void ResolveColumns(const std::string& source,
                    std::size_t data_columns,
                    bool parse_gyro,
                    LogOptions* options,
                    LogLayout* layout) {
  const Naming& naming = options->gyroscope_only ? kGyroLogNaming : kLogNaming;
  std::vector<ColumnSpec> specs;
  std::string problem = ParseColumnSpec(options->columns, &specs);
  for (ColumnSpec& spec : specs) {
    if (!naming.gyroscope_only || !problem.empty()) break;
    // A gyroscope's own log is mapped with the gyroscope's keys; its
    // readings take the accelerometer's places.
    if (spec.role >= kAx && spec.role <= kAz) {
      problem = fmt::format("key '{}' is not a gyroscope's (known: t, gx, gy, gz)",
                            kRoleKeys[spec.role]);
    } else if (spec.role >= kGx) {
      spec.role = static_cast<Role>(kAx + (spec.role - kGx));
    }
  }
  if (!problem.empty()) {
    throw Error(ErrorKind::kOption, "columns: " + problem, Give({{naming.option, ""}}));
  }
  ColumnOfRole column;
  column.fill(-1);
  if (layout->header_line > 0) {
    MapFromHeader(source, std::move(specs), naming, options, layout, &column);
  } else {
    MapWithoutHeader(source, specs, data_columns, naming, *options, &column);
  }
  CheckMapping(source, *layout, naming, *options, column);
  layout->time_column = column[kTime];
  for (int i = 0; i < 3; ++i) {
    layout->accel_columns[i] = column[kAx + i];
    layout->gyro_columns[i] = column[kGx + i];
  }
  int max_column = 0;
  for (int r = kTime; r <= kGz; ++r) {
    if (r >= kGx && !parse_gyro) continue;
    max_column = std::max(max_column, column[r]);
  }
  layout->min_columns = max_column + 1;
}

}  // namespace mpcal::logio
