// The refusal of rows holding a NaN or an infinity (not_finite.h).
#include "mpcal/not_finite.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>

namespace mpcal {
namespace {

std::string_view ColumnWords(RowColumn column) {
  switch (column) {
    case RowColumn::kTime:
      return "time";
    case RowColumn::kAccel:
      return "accelerometer reading";
    case RowColumn::kGyro:
      return "gyroscope reading";
  }
  return "time";
}

// Whether none of `n` doubles is NaN or infinite (all exponent bits set).
// On the bits, without a branch per value, which the compiler vectorises
// (std::isfinite it does not).
bool AllFinite(const double* values, std::size_t n) {
  constexpr std::uint64_t kExponent = 0x7ff0000000000000ULL;
  std::uint64_t not_finite = 0;
  for (std::size_t i = 0; i < n; ++i) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, values + i, sizeof bits);
    not_finite |= static_cast<std::uint64_t>((bits & kExponent) == kExponent);
  }
  return not_finite == 0;
}

// The doubles of `column`'s rows [begin, end) and how many per row.
std::span<const double> Values(const RecordingView& rows,
                               RowColumn column,
                               std::size_t begin,
                               std::size_t end,
                               std::size_t* per_row) {
  *per_row = column == RowColumn::kTime ? 1 : 3;
  const double* first = nullptr;
  switch (column) {
    case RowColumn::kTime:
      first = rows.time_s.data();
      break;
    case RowColumn::kAccel:
      first = rows.accel.empty() ? nullptr : rows.accel.front().data();
      break;
    case RowColumn::kGyro:
      first = rows.gyro_radps.empty() ? nullptr : rows.gyro_radps.front().data();
      break;
  }
  if (first == nullptr || end <= begin) return {};
  return {first + *per_row * begin, *per_row * (end - begin)};
}

}  // namespace

NotFiniteError::NotFiniteError(std::string_view source,
                               RowColumn column,
                               std::size_t row,
                               double value)
    : Error(ErrorKind::kInput,
            // (The value is NaN or ±inf, which to_string spells as such.)
            std::string(source.empty() ? std::string_view("recording") : source) +
                ": sample " + std::to_string(row) + " is not finite: its " +
                std::string(ColumnWords(column)) + " is " + std::to_string(value)),
      column_(column),
      row_(row) {}

void RefuseNotFinite(const RecordingView& rows,
                     RowColumn column,
                     std::size_t begin,
                     std::size_t end) {
  std::size_t per_row = 1;
  const std::span<const double> values = Values(rows, column, begin, end, &per_row);
  constexpr std::size_t kBlock = 4096;  // doubles: 32 KiB, within the L1 cache
  for (std::size_t b = 0; b < values.size(); b += kBlock) {
    const std::size_t n = std::min(kBlock, values.size() - b);
    if (AllFinite(values.data() + b, n)) continue;
    for (std::size_t i = b; i < b + n; ++i) {
      if (!std::isfinite(values[i])) {
        throw NotFiniteError(rows.source, column, begin + i / per_row, values[i]);
      }
    }
  }
}

void RefuseNotFinite(const RecordingView& rows, std::size_t begin, std::size_t end) {
  // Each column in turn, then the first bad row of all: a message names the
  // first row that cannot be used, whichever column it is in.
  std::size_t first_bad = end;
  RowColumn first_column = RowColumn::kTime;
  double first_value = 0.0;
  for (const RowColumn column : {RowColumn::kTime, RowColumn::kAccel, RowColumn::kGyro}) {
    if (column == RowColumn::kGyro && rows.gyro_radps.size() != rows.size()) continue;
    try {
      RefuseNotFinite(rows, column, begin, first_bad);
    } catch (const NotFiniteError& e) {
      first_bad = e.row();
      first_column = column;
      std::size_t per_row = 1;
      const auto values = Values(rows, column, first_bad, first_bad + 1, &per_row);
      first_value = *std::find_if(
          values.begin(), values.end(), [](double v) { return !std::isfinite(v); });
    }
  }
  if (first_bad < end)
    throw NotFiniteError(rows.source, first_column, first_bad, first_value);
}

}  // namespace mpcal
