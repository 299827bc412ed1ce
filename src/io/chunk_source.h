// The chunk source: a log's bytes from its file descriptor, either line by
// line (LineReader, for LogScanner) or as chunks of whole lines parsed on two
// threads (ChunkPipeline, for ReadLog). Private to src/io.
#pragma once

#include <array>
#include <condition_variable>
#include <cstddef>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include <Eigen/Core>

#include "row_parser.h"

namespace mpcal::logio {

/// A line longer than this means the input is not a log (binary junk, or a
/// file without line ends).
inline constexpr std::size_t kMaxLineBytes = std::size_t{1} << 19;
/// The first bytes read to find the layout (and LineReader's first buffer).
inline constexpr std::size_t kChunkBytes = std::size_t{1} << 20;
/// The size of a chunk ChunkPipeline parses: large enough that read(2) calls
/// and per-chunk bookkeeping vanish next to number parsing (a thousand rows),
/// small enough that the chunks in flight and their parsed rows (about 1.5
/// times the bytes) stay small beside the rows a short log is read into.
inline constexpr std::size_t kParseChunkBytes = std::size_t{1} << 16;

/// Bytes in pages of their own (a mapping), given back to the system when
/// freed. For the head a log's layout is found in: a mebibyte read once, which
/// from the heap would stay resident, free, beside the rows read after it.
/// (In the sanitizer builds the bytes come from the heap, whose bounds the
/// sanitizer checks.)
class PageBuffer {
 public:
  /// \throws std::bad_alloc when no mapping can be made.
  explicit PageBuffer(std::size_t bytes);
  ~PageBuffer();
  PageBuffer(const PageBuffer&) = delete;
  PageBuffer& operator=(const PageBuffer&) = delete;

  char* data() { return data_; }
  const char* data() const { return data_; }
  std::size_t size() const { return size_; }
  /// Grows to `bytes`, the contents kept.
  /// \throws std::bad_alloc when no mapping can be made.
  void Grow(std::size_t bytes);
  /// Gives the bytes back now; size() is then 0.
  void Release();

 private:
  char* data_ = nullptr;
  std::size_t size_ = 0;
};

/// "line N: longer than ... KiB" as an Error.
[[noreturn]] void ThrowLineTooLong(const std::string& source, std::size_t line);

/// An open log: a file (or standard input for "-") and its size.
class LogFile {
 public:
  /// \throws mpcal::Error for a missing or unreadable file or a directory.
  explicit LogFile(const std::string& path);
  ~LogFile();
  LogFile(const LogFile&) = delete;
  LogFile& operator=(const LogFile&) = delete;

  /// The name used in messages (the path, or "<stdin>").
  const std::string& source() const { return source_; }
  /// The size of a regular file; 0 otherwise.
  std::uint64_t size() const { return size_; }
  bool eof() const { return eof_; }
  /// Reads up to `n` bytes into `dst`, or until the input ends when
  /// `fill` (pipes deliver a little at a time); returns the count. A read
  /// failure sets `*error` (the bytes before it are returned).
  std::size_t Read(char* dst, std::size_t n, bool fill, std::string* error);
  /// Moves to byte `offset` of a regular file opened by name, to read it
  /// again from there; false, with nothing done, for standard input.
  bool Seek(std::uint64_t offset);

 private:
  std::string source_;
  int fd_ = -1;
  bool owns_fd_ = false;
  bool eof_ = false;
  std::uint64_t size_ = 0;
};

/// A log's lines in order, from a buffer refilled as they are consumed.
class LineReader {
 public:
  /// Reads the first chunk (see head()).
  explicit LineReader(LogFile* file);

  /// The unconsumed bytes read so far: after construction, the first chunk.
  std::string_view head() const;
  /// Drops the first `n` unread bytes (a byte-order mark), not counted as a line.
  void Skip(std::size_t n);
  /// The next line (text without its end, and its end) or false at the end.
  /// \throws mpcal::Error for a read failure or an overlong line.
  bool Next(std::string_view* text, std::string_view* eol);
  std::size_t line_number() const { return line_number_; }
  /// Bytes consumed so far, and bytes read from the file.
  std::uint64_t consumed() const { return consumed_; }
  std::uint64_t bytes_read() const { return bytes_read_; }

 private:
  void Refill(bool fill);

  LogFile* file_;
  PageBuffer buf_;
  std::size_t begin_ = 0;  // first unconsumed byte
  std::size_t end_ = 0;    // one past the last byte read
  std::size_t line_number_ = 0;
  std::uint64_t consumed_ = 0;
  std::uint64_t bytes_read_ = 0;
};

/// The parsed rows of one chunk, handed to the row sink in file order.
struct ChunkRows {
  std::string_view bytes;       // the chunk's whole lines
  std::size_t header_line = 0;  // 1-based within the chunk; 0 for none
  /// One entry per data line before the first malformed one: time in
  /// seconds, or the chunk's own row index when the log has no time column.
  std::vector<double> time;
  std::vector<Eigen::Vector3d> accel;
  std::vector<Eigen::Vector3d> gyro;  // in rad/s (or counts), when parsed
  std::size_t lines = 0;              // lines in the chunk (up to a fatal failure)
  std::size_t last_row_line = 0;      // 1-based within the chunk
  std::size_t first_row_bytes = 0;
  bool has_content = false;      // a line that is not blank
  std::size_t failure_line = 0;  // first malformed data line, 0 for none
  std::string failure;           // its problem
  bool failure_fatal = false;    // something but blank lines follows it
  bool line_too_long = false;    // reading stopped at a line with no end in sight
  std::string read_error;        // reading stopped at a read failure
};

/// What turns a chunk's lines into rows.
struct RowConversion {
  const RowParser* parser = nullptr;
  double time_scale = 1.0;      // seconds per unit of the time column
  double gyro_scale = 1.0;      // to rad/s
  bool index_time = false;      // no time column: rows are numbered
  bool gyro = false;            // gyroscope columns parsed
  std::size_t header_line = 0;  // within the first chunk; 0 for none
  std::size_t header_end = 0;   // bytes through the header line: the first chunk's least
};

/// The rows of `bytes`, whole lines (the input's last may lack its end),
/// into `*rows` (reused: cleared first): up to the first malformed line, and
/// whether anything but blank lines follows it. `header_line`: the header's
/// 1-based line within `bytes`, 0 for none. The one conversion of ReadLog's
/// chunks and of a live stream's lines (src/record).
void ParseChunkLines(const RowConversion& conv,
                     std::string_view bytes,
                     std::size_t header_line,
                     ChunkRows* rows);

/// ReadLog is bound by turning text into numbers, so it parses on two
/// cores: the input is cut into chunks of whole lines, read in file order by
/// whichever thread is free; each is parsed into its own rows; the calling
/// thread takes the parsed chunks in file order (Next) and hands each back
/// (Release). Memory: kChunksInFlight chunks of about kParseChunkBytes
/// at most.
class ChunkPipeline {
 public:
  /// `first_bytes`: what was read before (the layout's head), from where the
  /// rows start; not copied whole: it must outlive the pipeline.
  ChunkPipeline(LogFile* file, std::string_view first_bytes, RowConversion conversion);
  ~ChunkPipeline();
  ChunkPipeline(const ChunkPipeline&) = delete;
  ChunkPipeline& operator=(const ChunkPipeline&) = delete;

  /// The next chunk in file order once parsed; nullptr after the last. The
  /// calling thread reads and parses chunks too while it waits.
  /// \throws what parsing threw (out of memory).
  const ChunkRows* Next();
  /// Hands back the chunk Next returned.
  void Release();
  /// Bytes of the input released so far.
  std::uint64_t consumed() const { return consumed_; }
  /// Stops the helper thread (also on destruction).
  void Stop();

 private:
  struct Slot;
  Slot* Claim(bool wait);
  bool Read(Slot* c);
  bool TakeFromHead(Slot* c);
  std::size_t FirstChunkBytes(const Slot* c) const;
  void Parse(Slot* c);
  void ParseLines(Slot* c) const;
  void Finish(Slot* c);
  bool NextReady() const;

  LogFile* file_;
  RowConversion conversion_;
  std::thread helper_;

  std::mutex read_mutex_;  // reading: one thread at a time, in file order
  std::string_view head_;  // the first bytes not yet in a chunk
  std::vector<char> carry_;
  std::uint64_t consumed_ = 0;  // the calling thread's

  mutable std::mutex mutex_;
  std::condition_variable ready_;
  static constexpr std::size_t kChunksInFlight = 4;
  std::array<std::unique_ptr<Slot>, kChunksInFlight> slots_;
  std::size_t claimed_ = 0;  // chunks read
  std::size_t merged_ = 0;
  bool input_done_ = false;
  bool stop_ = false;
};

}  // namespace mpcal::logio
