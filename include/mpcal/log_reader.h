/// \file log_reader.h
/// \brief Reading accelerometer logs: delimited text as loggers write it.
///
/// Accepted shapes: comma, semicolon, tab or whitespace separated (detected);
/// an optional header naming the columns; `#` and `%` comment lines; CRLF line
/// ends; extra columns ignored. Column names recognised case-insensitively:
/// time `t`/`time`/`timestamp`, accelerometer `ax`/`acc_x`/`accel_x`/`accX`
/// (and y, z), gyroscope `gx`/`gyr_x`/`gyro_x`/`gyrX` (and y, z), and a
/// sample counter `n_samples`/`sample`/`index` used as time with a rate. A
/// unit in brackets after a name (`ax[m/s2]`, `acc_x (g)`) is ignored.
/// Without a header the columns are t, ax, ay, az in order unless `columns`
/// says otherwise.
///
/// A recording (a ROS 1 bag, an MCAP file, a ROS 2 bag directory: bag.h) is
/// read as a log by ReadLog and ReadLogRows: each sensor_msgs/Imu message of
/// LogOptions::topic is a row, its time the header stamp (or the receive time:
/// LogOptions::recording_time) in seconds from the earliest message's, the
/// accelerometer in m/s² and the gyroscope in rad/s as ROS defines them (no
/// gyroscope when the first message marks its angular velocity as not
/// measured: covariance[0] = -1). A recording's messages are held and put
/// in time order, one kept per time (Recording::stamp_order counts what
/// that changed), so times that go back are not an error there; gaps are
/// reported as for a text log. Held: about 56 bytes a message, also for
/// ReadLogRows, which then hands the sorted rows over in pieces.
///
/// Three entry points: ReadLog reads a whole log into a Recording (for
/// calibration); ReadLogRows reads it the same way but hands the rows over
/// chunk by chunk instead of holding them (for analyses that need one pass,
/// such as the noise's cumulative sums); LogScanner streams it line by line,
/// keeping each line's bytes, for commands that rewrite a log. All read the
/// file in large chunks and parse numbers with fast_float, so memory does not
/// depend on the file's size beyond what the Recording itself holds.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "mpcal/recording.h"
#include "mpcal/units.h"

namespace mpcal {

/// Unit of the time column.
enum class TimeUnit {
  kAuto,
  kSeconds,
  kMilliseconds,
  kMicroseconds,
  kNanoseconds,
  kSampleIndex
};
/// "auto", "s", "ms", "us", "ns" or "index".
std::string_view ToString(TimeUnit unit);
/// Inverse of ToString (also "µs"); std::nullopt for an unknown name.
std::optional<TimeUnit> ParseTimeUnit(std::string_view name);

/// Which time a recording's (bag.h) message is read at.
enum class RecordingTime {
  kHeader,   ///< the message's header stamp (when the sensor sampled, as the driver says)
  kReceive,  ///< when the recorder received it (ROS 1 record time, MCAP log_time)
};
/// "header" or "receive".
std::string_view ToString(RecordingTime time);

struct LogOptions {
  /// Explicit column mapping "t=NAME|INDEX,ax=...,ay=...,az=...[,gx=...]";
  /// indices are 0-based. Keys not given are taken from the header when
  /// there is one. Empty: from the header, or t,ax,ay,az in order.
  std::string columns;
  /// Units of the accelerometer columns.
  AccelUnits units = AccelUnits::kMps2;
  /// The sensor_msgs/Imu topic to read when the input is a recording (a ROS 1
  /// bag, an MCAP file, a ROS 2 bag directory: see bag.h). Empty: the
  /// recording's only sensor_msgs/Imu topic. Ignored for text logs.
  std::string topic;
  /// The time of each message of a recording: its header stamp or its
  /// receive time. A text log has neither: kReceive is refused with one.
  RecordingTime recording_time = RecordingTime::kHeader;
  /// Units of the gyroscope columns: rad/s, or deg/s when true.
  bool gyro_in_dps = false;
  /// The gyroscope columns are raw ADC counts, kept as read
  /// (Recording::gyro_units kCounts; the scale is found from the turns).
  /// Takes precedence over gyro_in_dps.
  bool gyro_in_counts = false;
  /// Unit of the time column. kAuto: seconds for non-integer values; for
  /// integer timestamps ns/µs/ms detected from the typical sample spacing
  /// (or a sample index when `rate_hz` is given and the spacing is 1).
  TimeUnit time_unit = TimeUnit::kAuto;
  /// Sample rate (Hz) when the time column is a sample index (or absent);
  /// 0 = not given.
  double rate_hz = 0.0;
  /// Called now and then (at most about 100 times) with the fraction of the
  /// input read so far, in [0, 1]; only for regular files, whose size is
  /// known. Empty: no progress reports.
  std::function<void(double fraction)> progress;

  /// The log is a gyroscope's file of its own (gyro_log.h): its three
  /// reading columns (held in Recording::accel) are named by the header as a
  /// gyroscope's (gx, gyr_x, wx, x, ... and y, z), and `columns` maps them
  /// with the keys t, gx, gy, gz; a recording's messages give their angular
  /// velocity there.
  bool gyroscope_only = false;
  /// The gyroscope columns' units as gyro_in_dps and gyro_in_counts say.
  GyroUnits gyro_units() const {
    if (gyro_in_counts) return GyroUnits::kCounts;
    return gyro_in_dps ? GyroUnits::kDps : GyroUnits::kRadps;
  }

  /// Empty string when valid, otherwise names the first bad field.
  std::string Validate() const;
};

/// Reads a whole log into memory. `path` "-" reads standard input.
///
/// Duplicated timestamps are dropped and reported in Recording::warnings, as
/// are gaps in time, a detected integer time unit and a truncated last line.
///
/// \throws mpcal::Error for a missing or unreadable file, a directory, an
///   empty file or one with no data rows, binary data, a malformed line (not
///   the last one: a truncated last line is dropped with a warning), too few
///   columns, an unknown column name, non-finite values, invalid options, or
///   a time column that goes back. Messages name the file, the line number
///   and, for a bad value, the column.
Recording ReadLog(const std::string& path, const LogOptions& options);

/// What ReadLogRows found besides the rows themselves.
struct LogStreamSummary {
  /// The name used in messages (the path, or "<stdin>"), as Recording::source.
  std::string source;
  /// Rows handed over (duplicated timestamps dropped).
  std::size_t rows = 0;
  /// Time of the first and last row handed over, in seconds (as time_s).
  double first_time_s = 0.0;
  double last_time_s = 0.0;
  /// The log has gyroscope columns (the pieces' gyro_radps are filled).
  bool has_gyro = false;
  /// Exactly the warnings ReadLog would put in Recording::warnings.
  std::vector<std::string> warnings;
  /// As Recording::stamp_order.
  StampOrder stamp_order;
};

/// Reads a log as ReadLog does (same layout detection, same two-thread
/// parsing, same rules, errors and warnings) but hands the rows over in
/// pieces, in file order, instead of holding them: `consume` is called with a
/// Recording whose vectors hold only the next rows (a chunk's, about a
/// megabyte of text; units, gyro_units and source set as ReadLog sets them;
/// warnings empty; no duplicated timestamp; time strictly increasing across
/// calls). The Recording is reused between calls: copy what must outlive the
/// call. Memory stays at a few chunks whatever the log's length. An empty
/// `consume` reads the log and drops the rows (the summary alone).
///
/// Errors are thrown when reached, after the rows before them were handed
/// over: time going back, a malformed line with data after it, a read
/// failure; "no data rows" and a time beyond any clock after the last
/// piece. An exception thrown by `consume` stops reading and propagates.
///
/// \throws mpcal::Error as ReadLog.
LogStreamSummary ReadLogRows(const std::string& path,
                             const LogOptions& options,
                             const std::function<void(const Recording& rows)>& consume);

/// Where the columns of a log are, found from its first lines.
struct LogLayout {
  /// ',', ';', '\t', or ' ' for runs of blanks (spaces and tabs).
  char delimiter = ',';
  /// '.' or, for logs with decimal commas (delimiter ';', tab or blank), ','.
  char decimal_point = '.';
  /// 1-based line number of the header; 0 when the log has none.
  std::size_t header_line = 0;
  /// The header's names, or "column N" when there is no header.
  std::vector<std::string> column_names;
  /// 0-based column indices; -1 when absent (no time column: time from the
  /// sample index and the rate).
  int time_column = -1;
  std::array<int, 3> accel_columns = {-1, -1, -1};
  std::array<int, 3> gyro_columns = {-1, -1, -1};
  /// The time column's unit, resolved (never kAuto).
  TimeUnit time_unit = TimeUnit::kSeconds;
  /// Seconds per unit of the time column (1/rate for a sample index).
  double seconds_per_time_unit = 1.0;
  /// Fewest columns a data line must have.
  int min_columns = 4;

  bool has_gyro() const { return gyro_columns[0] >= 0; }
  /// "t = column 0 'time', ax = column 1 'ax', ..." for messages.
  std::string Describe() const;
};

/// One line of a log, as LogScanner returns it.
struct LogLine {
  /// The line's bytes without its end of line.
  std::string_view text;
  /// "\n", "\r\n", or "" for a last line without one.
  std::string_view eol;
  std::size_t line_number = 0;  ///< 1-based
  /// False for comments, blank lines and the header.
  bool is_data = false;
  /// Data lines only: the time column's raw value in its own unit (see
  /// LogLayout::time_unit), or the 0-based data row number when the log has
  /// no time column.
  double time_raw = 0.0;
  /// Data lines only: accelerometer readings in the log's units.
  Eigen::Vector3d accel = Eigen::Vector3d::Zero();
  /// Data lines only, when the scanner parses the gyroscope: as in the log.
  Eigen::Vector3d gyro = Eigen::Vector3d::Zero();
  /// Data lines only: byte range [first, second) of each accelerometer
  /// number within `text` (x, y, z), so that it can be replaced.
  std::array<std::pair<std::uint32_t, std::uint32_t>, 3> accel_span{};
  /// The same for the gyroscope numbers, when the scanner parses them.
  std::array<std::pair<std::uint32_t, std::uint32_t>, 3> gyro_span{};
};

/// Streams a log line by line. Comments, blank lines and the header are
/// returned too (is_data false), so that a rewriter can copy them. A
/// malformed last line is withheld and reported in warnings().
class LogScanner {
 public:
  /// Opens `path` ("-": standard input) and reads its first lines to find
  /// the layout. `parse_gyro`: also parse the gyroscope columns.
  /// \throws mpcal::Error as ReadLog for an unusable file, invalid options,
  ///   or a layout that cannot be found (no data line, unknown columns).
  LogScanner(const std::string& path, const LogOptions& options, bool parse_gyro = false);
  ~LogScanner();
  LogScanner(const LogScanner&) = delete;
  LogScanner& operator=(const LogScanner&) = delete;

  const LogLayout& layout() const;
  /// The name used in messages (the path, or "<stdin>").
  const std::string& source() const;
  /// Next line into `*line`; its views stay valid until the next call.
  /// Returns false at the end of the input.
  /// \throws mpcal::Error for a read failure or a malformed line that is not
  ///   the last one.
  bool Next(LogLine* line);
  /// Non-fatal findings so far (truncated last line, detected time unit).
  const std::vector<std::string>& warnings() const;
  /// Bytes consumed so far, and the input's size (0 when not a regular file).
  std::uint64_t bytes_read() const;
  std::uint64_t total_bytes() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace mpcal
