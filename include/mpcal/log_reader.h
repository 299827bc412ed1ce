/// \file log_reader.h
/// \brief Reading accelerometer logs: delimited text as loggers write it.
///
/// Accepted shapes: comma, semicolon, tab or whitespace separated (detected);
/// an optional header naming the columns; `#` and `%` comment lines; CRLF line
/// ends; extra columns ignored. Column names recognised case-insensitively:
/// time `t`/`time`/`timestamp`, accelerometer `ax`/`acc_x`/`accel_x`/`accX`
/// (and y, z), gyroscope `gx`/`gyr_x`/`gyro_x`/`gyrX` (and y, z). Without a
/// header the columns are t, ax, ay, az in order unless `columns` says
/// otherwise.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "mpcal/recording.h"
#include "mpcal/units.h"

namespace mpcal {

/// Unit of the time column.
enum class TimeUnit { kAuto, kSeconds, kMilliseconds, kMicroseconds, kNanoseconds, kSampleIndex };
std::string_view ToString(TimeUnit unit);
std::optional<TimeUnit> ParseTimeUnit(std::string_view name);  // "s","ms","us","ns","index","auto"

struct LogOptions {
  /// Explicit column mapping "t=NAME|INDEX,ax=...,ay=...,az=...[,gx=...]";
  /// indices are 0-based. Empty: from the header, or t,ax,ay,az in order.
  std::string columns;
  /// Units of the accelerometer columns.
  AccelUnits units = AccelUnits::kMps2;
  /// Units of the gyroscope columns: rad/s, or deg/s when true.
  bool gyro_in_dps = false;
  /// Unit of the time column. kAuto: seconds for non-integer values; for
  /// integer timestamps ns/µs/ms detected from the typical sample spacing.
  TimeUnit time_unit = TimeUnit::kAuto;
  /// Sample rate (Hz) when the time column is a sample index (or absent);
  /// 0 = not given.
  double rate_hz = 0.0;

  /// Empty string when valid, otherwise names the first bad field.
  std::string Validate() const;
};

/// Reads a whole log into memory. `path` "-" reads standard input.
///
/// \throws mpcal::Error for a missing or unreadable file, a directory, an
///   empty file or one with no data rows, a malformed line (not the last one:
///   a truncated last line is dropped with a warning), too few columns, an
///   unknown column name, non-finite values, or a time column that goes back.
Recording ReadLog(const std::string& path, const LogOptions& options);

}  // namespace mpcal
