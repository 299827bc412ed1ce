// Layout detection: a log's first bytes in, its layout out (delimiter,
// decimal point, header, column mapping, time unit), with the boot text to
// skip and what is worth a warning. No file access: the caller reads the
// first chunk and hands it over. Private to src/io.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "log_text.h"
#include "mpcal/log_reader.h"

namespace mpcal::logio {

/// What detection found in a log's first bytes.
struct DetectedLayout {
  LogLayout layout;
  /// The role of each column up to layout.min_columns (kNone: not parsed).
  std::vector<Role> roles;
  /// Bytes of a UTF-8 byte-order mark at the start (0 or 3): never data.
  std::size_t bom_bytes = 0;
  /// Serial boot text before the header or data: its lines (counted after
  /// the byte-order mark), and the offset in the input where what follows
  /// it starts (0 when none is skipped).
  std::size_t skipped_lines = 0;
  std::size_t skipped_bytes = 0;
  /// Findings worth a warning (boot text skipped, a detected time unit).
  std::vector<std::string> warnings;
};

/// A line of at least three numbers and nothing else, whatever separates
/// them: what layout detection takes for a data row. (A live stream waits for
/// enough of them before it detects its layout.)
bool IsNumberRow(std::string_view text);

/// Finds the layout of a log from `head`, its first bytes (a megabyte or
/// so; `whole_input` when that is all of it). `source` names it in messages.
/// `parse_gyro`: the gyroscope columns are parsed too (they count towards
/// min_columns).
/// \throws mpcal::Error for an empty or binary input, no data line, a
///   header without rows, unmappable columns, or an unusable time column.
DetectedLayout DetectLayout(std::string_view head,
                            bool whole_input,
                            const std::string& source,
                            const LogOptions& options,
                            bool parse_gyro);

}  // namespace mpcal::logio
