#include "row_sink.h"

#include <sys/mman.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <utility>

#include <fmt/format.h>

#include "mpcal/error.h"
#include "mpcal/plausible.h"

namespace mpcal::logio {
namespace {

// Asks for huge pages under a long recording's arrays: filling them then
// costs a page fault every 2 MiB instead of every 4 KiB (a fifth of the
// reading time of a long log went to page faults).
template <typename T>
void AdviseHugePages(std::vector<T>& v) {
#ifdef MADV_HUGEPAGE
  constexpr std::size_t kHuge = std::size_t{1} << 21;
  char* const begin = reinterpret_cast<char*>(v.data());
  const auto address = reinterpret_cast<std::uintptr_t>(begin);
  const std::size_t skip = (kHuge - address % kHuge) % kHuge;
  const std::size_t bytes = v.capacity() * sizeof(T);
  if (bytes >= skip + kHuge) {
    ::madvise(begin + skip, (bytes - skip) / kHuge * kHuge, MADV_HUGEPAGE);
  }
#else
  (void)v;
#endif
}

// A logger's timestamp that is a 16- or 32-bit counter wraps around to 0:
// when time goes back from just below 2^N of its units, say so.
std::string CounterWrapHint(double raw_time_before) {
  for (const int bits : {16, 32}) {
    const double wrap = std::ldexp(1.0, bits);
    if (raw_time_before > 0.99 * wrap && raw_time_before < wrap) {
      return fmt::format(
          " (the timestamp looks like a {}-bit counter that wrapped around at {:.0f}: "
          "unwrap it, or leave time out of the column mapping and give the sample rate)",
          bits,
          wrap);
    }
  }
  return "";
}

}  // namespace

void ProgressReporter::Update(std::uint64_t done_bytes, bool at_end) {
  if (!report_ || total_ == 0) return;
  const double fraction =
      std::min(1.0, static_cast<double>(done_bytes) / static_cast<double>(total_));
  if (fraction - last_ >= 0.01 || (at_end && last_ < 1.0)) {
    last_ = fraction;
    report_(fraction);
  }
}

void ProgressReporter::Finish() {
  if (!report_ || total_ == 0 || last_ >= 1.0) return;
  last_ = 1.0;
  report_(1.0);
}

void CutOffLine::Hold(std::size_t line, std::string problem) {
  line_ = line;
  problem_ = std::move(problem);
}

void CutOffLine::Throw(const std::string& source) const {
  throw Error(ErrorKind::kInput, fmt::format("{}:{}: {}", source, line_, problem_));
}

std::string CutOffLine::Warning(const std::string& source) const {
  return fmt::format(
      "{}:{}: last line is incomplete ({}); ignored, as when a logger is cut off "
      "mid-write",
      source,
      line_,
      problem_);
}

GapCounter ReaderGapCounter() { return GapCounter(10000, 5.0); }

std::string GapWarning(const GapCounter& gaps, const std::string& source) {
  if (gaps.gaps() == 0) return "";
  return fmt::format(
      "{}: {} gap{} in time longer than 5 sample periods ({:.4g} s); the largest is "
      "{:.4g} s after t = {:.9g} s",
      source,
      gaps.gaps(),
      gaps.gaps() == 1 ? "" : "s",
      gaps.typical_s(),
      gaps.largest_s(),
      gaps.largest_at_s());
}

RowSink::RowSink(Recording* rec,
                 double time_scale,
                 bool index_time,
                 std::size_t line_base,
                 std::uint64_t total_bytes)
    : rec_(rec),
      time_scale_(time_scale),
      index_time_(index_time),
      line_base_(line_base),
      total_bytes_(total_bytes) {}

void RowSink::StreamTo(std::function<void(const Recording&)> consume) {
  consume_ = std::move(consume);
}

// clear() keeps the capacity: the next chunk's rows go into memory already
// faulted in, so streaming a long log costs no fresh pages.
void RowSink::HandOver() {
  if (!consume_ || rec_->time_s.empty()) return;
  consume_(*rec_);
  rec_->time_s.clear();
  rec_->accel.clear();
  rec_->gyro_radps.clear();
}

// Sizes the arrays once, from the first row's length (or the chunk's
// average, if shorter), so that a long log does not pay for repeated
// doubling (and twice the memory). Not when streaming: the arrays then hold
// a chunk's rows at most, and keep that capacity from chunk to chunk.
void RowSink::Reserve(const ChunkRows& c) {
  const std::size_t rows = c.time.size();
  if (consume_ || reserved_ || rows == 0 || total_bytes_ == 0) return;
  const double bytes_per_row = std::min(static_cast<double>(c.first_row_bytes),
                                        static_cast<double>(c.bytes.size()) / rows);
  const auto estimate = static_cast<std::size_t>(1.1 * static_cast<double>(total_bytes_) /
                                                 std::max(bytes_per_row, 8.0));
  rec_->time_s.reserve(estimate);
  rec_->accel.reserve(estimate);
  AdviseHugePages(rec_->time_s);
  AdviseHugePages(rec_->accel);
  if (!c.gyro.empty()) {
    rec_->gyro_radps.reserve(estimate);
    AdviseHugePages(rec_->gyro_radps);
  }
  reserved_ = true;
}

// The file's line number of a chunk's `row`th stored row: only needed for
// messages, so found again by walking the lines.
std::size_t RowSink::LineOf(const ChunkRows& c, std::size_t row) const {
  if (row + 1 == c.time.size()) return line_base_ + c.last_row_line;
  const char* p = c.bytes.data();
  const char* const end = p + c.bytes.size();
  std::size_t line = 0;
  std::size_t rows = 0;
  while (p < end) {
    const auto* nl = static_cast<const char*>(std::memchr(p, '\n', end - p));
    const char* const stop = nl != nullptr ? nl : end;
    std::string_view text(p, static_cast<std::size_t>(stop - p));
    if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
    p = nl != nullptr ? nl + 1 : end;
    ++line;
    if (line == c.header_line || IsCommentOrBlank(text)) continue;
    if (rows++ == row) break;
  }
  return line_base_ + line;
}

void RowSink::ThrowTimeBack(const ChunkRows& c, std::size_t row, std::size_t kept) {
  if (kept < c.time.size()) previous_line_ = LineOf(c, kept);
  const double t =
      index_time_ ? static_cast<double>(rows_before_ + row) * time_scale_ : c.time[row];
  const double before = last_time_s_;
  HandOver();  // the rows before the error
  throw Error(ErrorKind::kTime,
              fmt::format("{}:{}: time goes back: {:.9g} s after {:.9g} s on {} {}; "
                          "the rows must be in time order{}",
                          rec_->source,
                          LineOf(c, row),
                          t,
                          before,
                          row_noun_,
                          previous_line_,
                          CounterWrapHint(before / time_scale_)));
}

// A run of rows kept, each later than the one before.
void RowSink::CountRun(std::span<const double> time) {
  if (rows_ == 0) first_time_s_ = time.front();
  rows_ += time.size();
  last_time_s_ = time.back();
  gaps_.Add(time);
}

// Runs of rows each later than the one before are copied at once; a row at
// the same time as the one before is dropped and counted.
void RowSink::AppendRows(const ChunkRows& c) {
  const std::size_t rows = c.time.size();
  std::vector<double> numbered;
  if (index_time_) {
    numbered.reserve(rows);
    for (std::size_t j = 0; j < rows; ++j) {
      numbered.push_back(static_cast<double>(rows_before_ + j) * time_scale_);
    }
  }
  const std::vector<double>& time = index_time_ ? numbered : c.time;
  const bool gyro = !c.gyro.empty();
  std::size_t j = 0;
  std::size_t last_kept = rows;  // none yet in this chunk
  while (j < rows) {
    std::size_t k = j;
    double previous = rows_ == 0 ? time[k++] : last_time_s_;
    while (k < rows && time[k] > previous) previous = time[k++];
    if (k > j) {
      CountRun(std::span<const double>(time).subspan(j, k - j));
      rec_->time_s.insert(rec_->time_s.end(), time.begin() + j, time.begin() + k);
      rec_->accel.insert(rec_->accel.end(), c.accel.begin() + j, c.accel.begin() + k);
      if (gyro) {
        rec_->gyro_radps.insert(
            rec_->gyro_radps.end(), c.gyro.begin() + j, c.gyro.begin() + k);
      }
      last_kept = k - 1;
    }
    if (k == rows) break;
    if (time[k] != last_time_s_) ThrowTimeBack(c, k, last_kept);
    if (duplicates_++ == 0) first_duplicate_line_ = LineOf(c, k);
    j = k + 1;
  }
  if (last_kept < rows) previous_line_ = LineOf(c, last_kept);
}

void RowSink::Append(const ChunkRows& c) {
  if (cut_off_.held() && c.has_content) cut_off_.Throw(rec_->source);
  if (!cut_off_.held()) {
    Reserve(c);
    AppendRows(c);
    HandOver();
    rows_before_ += c.time.size();
    if (c.failure_line > 0) {
      cut_off_.Hold(line_base_ + c.failure_line, c.failure);
      if (c.failure_fatal) cut_off_.Throw(rec_->source);
    }
  }
  line_base_ += c.lines;
  if (c.line_too_long) ThrowLineTooLong(rec_->source, line_base_ + 1);
  if (!c.read_error.empty()) throw Error(ErrorKind::kIo, c.read_error);
}

void RowSink::Adopt(ChunkRows&& c) {
  const bool increasing =
      std::adjacent_find(c.time.begin(), c.time.end(), [](double a, double b) {
        return b <= a;
      }) == c.time.end();
  if (consume_ || rows_ > 0 || index_time_ || c.time.empty() || !increasing ||
      c.failure_line > 0 || c.line_too_long || !c.read_error.empty()) {
    Append(c);
    return;
  }
  CountRun(c.time);
  rec_->time_s.swap(c.time);
  rec_->accel.swap(c.accel);
  if (!c.gyro.empty()) rec_->gyro_radps.swap(c.gyro);
  rows_before_ += rec_->time_s.size();
  previous_line_ = line_base_ + c.last_row_line;
  line_base_ += c.lines;
}

// Times that do not advance, or advance by less than any sensor samples,
// leave every duration of the log meaningless: detection's windows would
// hold no rows (a threshold of NaN) or all of them.
void RowSink::CheckSamplePeriod() const {
  const Advice advice{
      {{Option::kLogTimeUnit, ""}, {Option::kLogRate, ""}}, Stage::kNone, ""};
  if (rows_ == 1 && duplicates_ > 0) {
    throw Error(ErrorKind::kTime,
                fmt::format("{}: all {} rows have the same time, {:.9g} s: the time "
                            "column does not advance",
                            rec_->source,
                            duplicates_ + 1,
                            first_time_s_),
                advice);
  }
  if (rows_ < 2) return;
  // The median step, or the mean when too few steps give a median.
  const double step = gaps_.typical_s() > 0.0 ? gaps_.typical_s()
                                              : (last_time_s_ - first_time_s_) /
                                                    static_cast<double>(rows_ - 1);
  if (step >= kMinSamplePeriodS) return;
  throw Error(ErrorKind::kTime,
              fmt::format("{}: the time steps are {:.3g} s, shorter than any sensor "
                          "samples (at most {:g} Hz, a step of {:g} s): the time column "
                          "is not a time in the unit it is read in",
                          rec_->source,
                          step,
                          kMaxSampleRateHz,
                          kMinSamplePeriodS),
              advice);
}

void RowSink::Finish(bool has_header) {
  if (cut_off_.held()) rec_->warnings.push_back(cut_off_.Warning(rec_->source));
  if (rows_ == 0) {
    throw Error(ErrorKind::kInput,
                fmt::format("'{}' has no data rows{}",
                            rec_->source,
                            has_header ? " after its header" : ""));
  }
  // Rows are in time order: the first and last times bound them all.
  for (const double t : {first_time_s_, last_time_s_}) {
    if (std::abs(t) > kMaxTimeS) {
      throw Error(ErrorKind::kTime,
                  fmt::format("{}: a time of {:.6g} s is beyond any logger's clock (more "
                              "than {:g} s, 31,700 years): the time column is not a time "
                              "in the unit it is read in",
                              rec_->source,
                              t,
                              kMaxTimeS));
    }
  }
  gaps_.Finish();
  CheckSamplePeriod();
  if (duplicates_ > 0) {
    rec_->warnings.push_back(
        fmt::format("{}: {} row{} with a duplicated timestamp dropped (first on {} {})",
                    rec_->source,
                    duplicates_,
                    duplicates_ == 1 ? "" : "s",
                    row_noun_,
                    first_duplicate_line_));
  }
  std::string gaps = GapWarning(gaps_, rec_->source);
  if (!gaps.empty()) rec_->warnings.push_back(std::move(gaps));
}

}  // namespace mpcal::logio
