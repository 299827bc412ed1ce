// The row sink: where parsed rows become a Recording, with the rules every
// reader of a log keeps in one place: duplicated timestamps dropped and
// counted, time going back refused (with a hint for a counter that wrapped),
// a malformed last line dropped with a warning (a logger cut off mid-write)
// but a malformed line with data after it refused, progress reported, gaps
// and impossible times found. The rows are either held in a Recording or
// handed over chunk by chunk (streaming). Private to src/io.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "chunk_source.h"
#include "mpcal/gap_counter.h"
#include "mpcal/recording.h"

namespace mpcal::logio {

/// Reports the fraction of the input done, at most about 100 times, the
/// last one 1.0; nothing when the size is unknown or there is no callback.
class ProgressReporter {
 public:
  ProgressReporter(std::function<void(double)> report, std::uint64_t total_bytes)
      : report_(std::move(report)), total_(total_bytes) {}
  void Update(std::uint64_t done_bytes, bool at_end = false);
  void Finish();

 private:
  std::function<void(double)> report_;
  std::uint64_t total_;
  double last_ = -1.0;
};

/// A malformed data line: fatal if anything but blank lines follows it,
/// else a cut-off last line, dropped with a warning.
class CutOffLine {
 public:
  void Hold(std::size_t line, std::string problem);
  bool held() const { return line_ > 0; }
  /// \throws mpcal::Error "SOURCE:LINE: problem".
  [[noreturn]] void Throw(const std::string& source) const;
  /// The warning for a held line at the end of the input.
  std::string Warning(const std::string& source) const;

 private:
  std::size_t line_ = 0;
  std::string problem_;
};

/// The reader's rule for gaps in time: steps longer than 5 typical ones, the
/// typical step the median of the first 10,000 (GapCounter: reading a log
/// whole or in pieces gives the same warning).
GapCounter ReaderGapCounter();
/// The warning for the gaps counted (after GapCounter::Finish), "" for none.
std::string GapWarning(const GapCounter& gaps, const std::string& source);

/// Appends the rows of chunks, in file order, to a Recording: all of them
/// (holding), or each chunk's then handed over (streaming, see StreamTo).
class RowSink {
 public:
  /// `time_scale`: seconds per unit of the time column (for messages and
  /// numbered rows); `line_base`: lines of the input before the first
  /// chunk; `total_bytes`: the input's size, 0 if unknown.
  RowSink(Recording* rec,
          double time_scale,
          bool index_time,
          std::size_t line_base,
          std::uint64_t total_bytes);

  /// Streaming: after each chunk, `consume` is called with the Recording
  /// holding that chunk's rows only, whose vectors are then cleared (their
  /// capacity kept, so the memory is reused). Call before the first Append.
  void StreamTo(std::function<void(const Recording&)> consume);

  /// Appends a chunk's rows (and, streaming, hands them over: also those
  /// before an error, which is thrown after).
  /// \throws mpcal::Error for time going back, a malformed line with data
  ///   after it, an overlong line or a read failure.
  void Append(const ChunkRows& c);

  /// As Append for rows in strictly increasing time with no malformed line;
  /// when holding and nothing is held yet, the arrays of `c` are taken, not
  /// copied (a recording put in time order in memory: no second copy).
  void Adopt(ChunkRows&& c);

  /// Checks the whole and adds the warnings (cut-off last line,
  /// duplicates, gaps). `has_header`: for the message when there are no rows.
  /// \throws mpcal::Error for no rows or a time beyond any clock.
  void Finish(bool has_header);

  /// What the input's numbered units are called in messages ("line"; a
  /// recording's rows are "message"s).
  void NameRows(std::string noun) { row_noun_ = std::move(noun); }

  /// Rows kept so far (duplicates dropped), and the first and last time.
  std::size_t rows() const { return rows_; }
  double first_time_s() const { return first_time_s_; }
  double last_time_s() const { return last_time_s_; }

 private:
  void Reserve(const ChunkRows& c);
  void AppendRows(const ChunkRows& c);
  void CountRun(std::span<const double> time);
  void CheckSamplePeriod() const;
  [[noreturn]] void ThrowTimeBack(const ChunkRows& c, std::size_t row, std::size_t kept);
  std::size_t LineOf(const ChunkRows& c, std::size_t row) const;
  void HandOver();

  Recording* rec_;
  double time_scale_;
  bool index_time_;
  std::size_t line_base_;  // lines before the chunk being appended
  std::uint64_t total_bytes_;
  std::size_t rows_before_ = 0;
  std::size_t duplicates_ = 0;
  std::size_t first_duplicate_line_ = 0;
  std::size_t previous_line_ = 0;  // of the last row kept
  std::size_t rows_ = 0;           // kept, handed over or not
  double first_time_s_ = 0.0;
  double last_time_s_ = 0.0;  // of the last row kept
  bool reserved_ = false;
  CutOffLine cut_off_;
  GapCounter gaps_ = ReaderGapCounter();
  std::function<void(const Recording&)> consume_;  // empty: holding
  std::string row_noun_ = "line";
};

}  // namespace mpcal::logio
