/// \file live_source.h
/// \brief A live IMU stream: its bytes as they arrive, its lines parsed as
/// every log is, and the session file written as it arrives.
///
/// Three pieces that a recording loop strings together:
///
///   auto source = OpenLiveSource({"tcp:imu.local:5000"});
///   LiveLogParser parser(log_options, source->source());
///   SessionWriter session("session.csv", source->source());
///   std::string bytes;
///   Recording rows;
///   while (source->Read(&bytes, 0.05)) {
///     rows.time_s.clear(); ...                 // the caller clears the rows
///     parser.Feed(bytes, &rows);
///     bytes.clear();
///     session.Write(parser.TakeSessionText());
///     ... use rows; at a captured position: session.Flush();
///   }
///   parser.Finish(&rows);
///   session.Write(parser.TakeSessionText());
///   session.Close();
///
/// Sources: standard input ("-"), a serial port (a path such as
/// /dev/ttyUSB0: raw 8N1 at LiveSourceOptions::baud), a TCP stream
/// ("tcp:HOST:PORT", IPv6 as "tcp:[::1]:PORT") and a UDP port ("udp:PORT",
/// bound on every address; a datagram holds whole lines). Every wait is a
/// poll(2) with a bound, so nothing hangs: a stream that sends nothing for
/// LiveSourceOptions::timeout_s is an Error that says it stopped.
#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "mpcal/log_reader.h"
#include "mpcal/recording.h"

namespace mpcal {

struct LiveSourceOptions {
  /// "-" standard input, "/dev/ttyUSB0" (any other path: a serial port),
  /// "tcp:HOST:PORT", "udp:PORT".
  std::string spec;
  /// Serial ports only: the baud rate (8 data bits, no parity, 1 stop bit).
  int baud = 115200;
  /// No byte for this long (s): an Error that says the stream stopped.
  double timeout_s = 5.0;

  /// Empty string when valid, otherwise names the first bad field.
  std::string Validate() const;
};

/// The kind of source a spec names.
enum class LiveSourceKind { kStdin, kSerial, kTcp, kUdp };
/// What `spec` names, without opening it.
/// \throws mpcal::Error (kOption) for an empty spec, or "tcp:"/"udp:" without
///   a usable host and port.
LiveSourceKind KindOfLiveSource(const std::string& spec);

/// Bytes as they arrive; one per session.
class LiveSource {
 public:
  virtual ~LiveSource();
  LiveSource() = default;
  LiveSource(const LiveSource&) = delete;
  LiveSource& operator=(const LiveSource&) = delete;

  /// Waits up to `wait_s` for bytes and appends what arrived to `*out`
  /// (returning as soon as some did). Returns false at the end of the stream
  /// (EOF, the peer closed); true otherwise, also when nothing arrived or a
  /// signal interrupted the wait (so that the caller can look at its flags).
  /// \throws mpcal::Error (kIo) on a read failure, and when nothing arrived
  ///   for timeout_s in total since the last byte (or since opening).
  virtual bool Read(std::string* out, double wait_s) = 0;
  /// The name used in messages ("<stdin>", the port's path, "tcp:HOST:PORT").
  virtual const std::string& source() const = 0;
  /// Bytes received so far.
  virtual std::size_t bytes_received() const = 0;
};

/// Opens the source `options.spec` names: a serial port is opened and set to
/// raw 8N1 at the baud rate; a TCP stream is connected (within timeout_s); a
/// UDP port is bound.
/// \throws mpcal::Error (kOption for a bad spec or options; kIo, naming the
///   source and what to do, for a port that does not exist, is busy, is not
///   permitted or refuses the baud rate, a host that cannot be resolved, a
///   connection refused or not made within timeout_s, a port already bound).
std::unique_ptr<LiveSource> OpenLiveSource(const LiveSourceOptions& options);

/// The lines of a live IMU stream parsed as every log is (ReadLog's layout
/// detection, column mapping, row parser and rules: same LogOptions), the
/// layout found from the first lines as they arrive (about 50 data lines, or
/// 64 KiB of text, or the end of the stream). Serial boot text and a cut
/// first line are skipped and counted as ReadLog skips them in a file.
/// Feeding the same bytes in any pieces gives the same rows, and the rows
/// are those ReadLog gives for the session text (TakeSessionText).
class LiveLogParser {
 public:
  LiveLogParser(const LogOptions& options, std::string source_name);
  ~LiveLogParser();
  LiveLogParser(const LiveLogParser&) = delete;
  LiveLogParser& operator=(const LiveLogParser&) = delete;

  /// Feeds bytes; appends the whole rows parsed (time_s in seconds, accel in
  /// the log's units as ReadLog keeps them, gyro_radps in rad/s when the log
  /// has a gyroscope) to `rows`, a Recording used as a row buffer that the
  /// caller clears; its units, gyro_units and source are set as ReadLog sets
  /// them. An incomplete last line is kept for the next call.
  /// \throws mpcal::Error as ReadLog (a stream that is not IMU lines, time
  ///   going back, a malformed line with data after it, ...), after appending
  ///   the rows before the error.
  void Feed(std::string_view bytes, Recording* rows);
  /// The end of the stream: the layout found from what came (if not yet),
  /// the last line parsed even without its end of line (a malformed one is
  /// dropped with a warning, as ReadLog drops a cut-off last line).
  /// \throws mpcal::Error as ReadLog (no data rows, ...).
  void Finish(Recording* rows);

  bool layout_known() const;
  /// The layout; only once layout_known().
  const LogLayout& layout() const;
  /// Lines skipped before the header or data: serial boot text, a cut line.
  std::size_t skipped_lines() const;
  /// Rows handed over so far (duplicated timestamps dropped).
  std::size_t rows() const;
  /// Non-fatal findings so far, as ReadLog words them (boot text skipped, a
  /// detected time unit; at Finish, a cut-off last line, duplicates, gaps).
  const std::vector<std::string>& warnings() const;

  /// The text the session file must hold, received since the last call: the
  /// header first (the stream's, as received, or the layout's column names
  /// when it has none), then every line whose rows were handed over (or that
  /// holds none: comments, blank lines), as received, each with its end of
  /// line. Boot text and a line that an Error refused are not in it, so that
  /// the session file is a log ReadLog reads to the same rows.
  std::string TakeSessionText();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

/// The session file, written as the text arrives. The output path rules of
/// every other output hold: never a device, a FIFO, a socket, a directory or
/// a symbolic link, never the input; a regular file there is replaced. The
/// file is created at the first text (a session that received nothing
/// leaves none and replaces none). Text reaches the kernel (write(2)) every
/// 4 KiB and at every Flush, so that a crash, a pulled cable or Ctrl-C
/// leaves a readable log. For Ctrl-C the command sets a flag in its SIGINT
/// handler, leaves its loop, and Close (or the destructor) finishes the
/// file: nothing more is needed.
class SessionWriter {
 public:
  /// Checks `path` (the rules above; its directory exists and is writable;
  /// not `input_spec`, the live source's spec, when that is a file).
  /// \throws mpcal::Error (kIo) naming the path and what to do.
  SessionWriter(const std::string& path, const std::string& input_spec);
  /// Closes as Close does; never throws.
  ~SessionWriter();
  SessionWriter(const SessionWriter&) = delete;
  SessionWriter& operator=(const SessionWriter&) = delete;

  /// Buffers `text` (whole lines, as LiveLogParser::TakeSessionText gives
  /// them); writes when 4 KiB are held.
  /// \throws mpcal::Error (kIo) when the file cannot be created or a write
  ///   fails (a full disk).
  void Write(std::string_view text);
  /// Writes what is buffered: in the kernel, on disk in time even if the
  /// process is killed.
  /// \throws mpcal::Error (kIo) on a write failure.
  void Flush();
  /// Flushes and closes. Returns true when a file was written (false: no
  /// text came, no file). Idempotent.
  /// \throws mpcal::Error (kIo) on a write failure (the file is kept as
  ///   far as it was written).
  bool Close();

  const std::string& path() const { return path_; }
  /// Bytes in the file so far (buffered ones not counted).
  std::size_t bytes_written() const { return written_; }

 private:
  void WriteAll(const char* data, std::size_t size);

  std::string path_;
  int fd_ = -1;
  std::string buffer_;
  std::size_t written_ = 0;
  bool closed_ = false;
  bool fd_kept_ = false;
};

}  // namespace mpcal
