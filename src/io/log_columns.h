// Which column of a log holds what: the names loggers give their columns,
// the explicit mapping (LogOptions::columns), and the mapping resolved from
// both. Part of layout detection; no file access. Private to src/io.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "log_text.h"
#include "mpcal/log_reader.h"

namespace mpcal::logio {

/// The role a header name gives its column ("Acc_X [m/s2]" -> kAx).
Role RoleOfName(std::string_view name);
/// The time unit a column's name states (`millis`, `Time (s)`), if any.
std::optional<TimeUnit> TimeUnitOfName(std::string_view name);
/// A sample counter's name (`n_samples`, `index`).
bool IsSampleIndexName(std::string_view name);

/// The fields of a line; `delimiter` ' ' splits at runs of blanks.
std::vector<std::string_view> SplitFields(std::string_view line, char delimiter);
/// The whole field (quotes and a leading '+' allowed) is one number.
bool ParsesAsNumber(std::string_view field, char decimal_point);
/// Digits only, after an optional sign (quotes allowed).
bool LooksLikeInteger(std::string_view field);

/// One item of a column mapping: a role and its column's name or index.
struct ColumnSpec {
  Role role = kNone;
  std::string name;  // empty when given by index
  int index = -1;
};

/// Parses "t=NAME|INDEX,ax=..."; returns "" or the problem.
std::string ParseColumnSpec(const std::string& spec, std::vector<ColumnSpec>* out);

/// Fills `layout`'s column indices and min_columns from its header names
/// (if any) and `options->columns`. A sample-counter column taken as time
/// sets `options->time_unit` to kSampleIndex when it was kAuto.
/// \throws mpcal::Error (kColumns, kTime) when a column cannot be found.
void ResolveColumns(const std::string& source,
                    std::size_t data_columns,
                    bool parse_gyro,
                    LogOptions* options,
                    LogLayout* layout);

}  // namespace mpcal::logio
