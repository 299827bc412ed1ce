/// \file log_writer.h
/// \brief Writing a Recording as a CSV log that ReadLog reads back.
///
/// Format: a header `t,ax,ay,az` (plus `,gx,gy,gz` when the recording has a
/// gyroscope), then one row per sample: time in seconds as the shortest
/// decimal that reads back to the same double; accelerometer readings in the
/// recording's own units (m/s², g, or counts written as integers);
/// gyroscope in rad/s. Line ends are "\n".
#pragma once

#include <ostream>
#include <string>

#include "mpcal/recording.h"

namespace mpcal {

struct LogWriteOptions {
  /// Significant digits of accelerometer (m/s² or g) and gyroscope values.
  /// 9 keeps 1e-8 relative: far below any accelerometer's noise, while the
  /// file stays a third smaller than with exact values. 0 = the shortest
  /// decimal that reads back to the same double (exact round trip). Counts
  /// that are whole numbers are always written as integers.
  int significant_digits = 9;

  /// "" when valid, otherwise names the first bad field.
  std::string Validate() const;
};

/// Writes the CSV text of `recording` to `out`.
/// \throws mpcal::Error for invalid options, a recording whose columns have
///   different lengths, or a non-finite value (naming its row), or when
///   `out` fails.
void WriteRecordingCsv(std::ostream& out,
                       const Recording& recording,
                       const LogWriteOptions& options = {});

/// Writes the CSV to `path` atomically (the file appears whole or not at
/// all; "-" is standard output).
/// \throws mpcal::Error as WriteRecordingCsv, or when the file cannot be
///   written (missing directory, no permission, disk full).
void WriteRecordingFile(const std::string& path,
                        const Recording& recording,
                        const LogWriteOptions& options = {});

}  // namespace mpcal
