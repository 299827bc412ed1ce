// The one parser of a log's data rows, for both the streaming scanner and
// the two-thread reader: one pass over the line, numbers straight from the
// bytes with fast_float, no allocation; columns that no role needs are
// skipped unparsed. The message for a malformed row is built only when it
// is needed (Problem). Private to src/io.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include <fast_float/fast_float.h>

#include "log_text.h"
#include "mpcal/log_reader.h"
#include "mpcal/units.h"

namespace mpcal::logio {

/// Why a data row did not parse: enough to build the message later, so that
/// rows can be parsed on several threads and only the first failure in file
/// order be spelled out.
struct RowFailure {
  enum class Kind { kTooFew, kBadNumber, kNonFinite, kImpossible };
  Kind kind = Kind::kTooFew;
  int column = 0;
  const char* at = nullptr;   // the field's (or the number's) first byte
  const char* end = nullptr;  // one past the number (kNonFinite, kImpossible)
};

class RowParser {
 public:
  /// `roles`: the role of each column up to the last one parsed. Readings
  /// beyond any accelerometer's range in `units` are refused.
  RowParser(const LogLayout& layout, std::vector<Role> roles, AccelUnits units);

  /// Parses one data line (without its end) into `out`'s time_raw, accel,
  /// gyro (for the roles given) and their spans; false when malformed, with
  /// `why` set.
  bool Parse(std::string_view text, LogLine* out, RowFailure* why) const;

  /// ReadLog's fast path: parses the data line that starts at `p`, in a
  /// chunk of lines ending at `end`, into `by_role` (indexed by Role),
  /// finding the line's end as it goes (no separate search for it). Returns
  /// where the next line starts, or nullptr for anything that is not a
  /// plain data row (a header, a comment, a malformed row, a stray '\r'):
  /// the caller then finds the line's end and calls Parse, whose verdict
  /// and message are the reference. Accepts a line exactly when Parse
  /// would, with the same values.
  const char* ParseInChunk(const char* p, const char* end, double* by_role) const;

  /// The message for a row Parse refused (without file and line).
  std::string Problem(std::string_view text, const RowFailure& why) const;

 private:
  // kInChunk: `stop` is the end of a chunk of lines, and a field may also
  // end at '\n' or '\r' (ParseInChunk checks what follows).
  template <bool kInChunk>
  const char* ParseField(const char* p,
                         const char* stop,
                         int column,
                         double* value,
                         const char** number_begin,
                         const char** number_end,
                         RowFailure* why) const;
  std::string ColumnLabel(int column) const;
  std::string TooFew(std::string_view text, int found) const;
  std::string BadNumber(std::string_view text, int column, const char* field_begin) const;

  LogLayout layout_;
  std::vector<Role> roles_;
  AccelUnits units_;
  double max_reading_;  // in units_
  fast_float::parse_options number_format_;
};

}  // namespace mpcal::logio
