/// \file not_finite.h
/// \brief The refusal of rows holding a NaN or an infinity, where they are
/// first read.
#pragma once

#include <cstddef>
#include <string_view>

#include "mpcal/error.h"
#include "mpcal/recording_view.h"

namespace mpcal {

/// The columns of a recording's rows, to say where a value is.
enum class RowColumn { kTime, kAccel, kGyro };

/// A row whose time or reading is NaN or infinite (kind kInput). A log
/// reader never gives one, but a RecordingView of the caller's memory may:
/// what reads a view first (static detection's first pass, the units check,
/// the noise analysis) refuses it rather than let it become a number. The
/// facts: the column and the row (0-based) of the first such value.
class NotFiniteError : public Error {
 public:
  NotFiniteError(std::string_view source,
                 RowColumn column,
                 std::size_t row,
                 double value);

  RowColumn column() const { return column_; }
  std::size_t row() const { return row_; }

 private:
  RowColumn column_;
  std::size_t row_;
};

/// Throws NotFiniteError for the first of rows [begin, end) of `rows` whose
/// time, acceleration or angular rate (when held, one per row) is NaN or
/// infinite, naming the first column that is; returns when every value is
/// finite. One vectorised pass over the rows.
void RefuseNotFinite(const RecordingView& rows, std::size_t begin, std::size_t end);

/// The same, only of `column` (kGyro: `rows.gyro_radps`, each of its rows).
void RefuseNotFinite(const RecordingView& rows,
                     RowColumn column,
                     std::size_t begin,
                     std::size_t end);

}  // namespace mpcal
