// The public face of the log reader: ReadLog, ReadLogRows and LogScanner, built from its
// parts (room-private headers beside this file):
//   log_layout   layout detection: first bytes in, a layout out (no file access)
//   log_columns  column names, the explicit mapping, the resolved mapping
//   row_parser   the one parser of a data row
//   chunk_source the file, its lines, and the two-thread chunk pipeline
//   row_sink     rows into a Recording (held, or handed over chunk by
//                chunk): duplicates, time going back, the cut-off last
//                line, gaps, progress
#include "mpcal/log_reader.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <numbers>
#include <optional>
#include <utility>

#include <fmt/format.h>

#include "bag_log.h"
#include "chunk_source.h"
#include "log_columns.h"
#include "log_layout.h"
#include "log_text.h"
#include "mpcal/bag.h"
#include "mpcal/error.h"
#include "row_parser.h"
#include "row_sink.h"

namespace mpcal {

using logio::Lower;
using logio::ParseColumnSpec;

std::string_view ToString(TimeUnit unit) {
  switch (unit) {
    case TimeUnit::kAuto:
      return "auto";
    case TimeUnit::kSeconds:
      return "s";
    case TimeUnit::kMilliseconds:
      return "ms";
    case TimeUnit::kMicroseconds:
      return "us";
    case TimeUnit::kNanoseconds:
      return "ns";
    case TimeUnit::kSampleIndex:
      return "index";
  }
  return "unknown";
}

std::string_view ToString(RecordingTime time) {
  return time == RecordingTime::kReceive ? "receive" : "header";
}

std::optional<TimeUnit> ParseTimeUnit(std::string_view name) {
  const std::string n = Lower(name);
  if (n == "auto") return TimeUnit::kAuto;
  if (n == "s") return TimeUnit::kSeconds;
  if (n == "ms") return TimeUnit::kMilliseconds;
  if (n == "us" || n == "\xc2\xb5s") return TimeUnit::kMicroseconds;
  if (n == "ns") return TimeUnit::kNanoseconds;
  if (n == "index") return TimeUnit::kSampleIndex;
  return std::nullopt;
}

std::string LogOptions::Validate() const {
  if (!std::isfinite(rate_hz) || rate_hz < 0.0) {
    return fmt::format("rate_hz must be a positive number of Hz (or 0 for none), got {}",
                       rate_hz);
  }
  if (time_unit == TimeUnit::kSampleIndex && rate_hz <= 0.0) {
    return "time_unit 'index' needs the sample rate: give rate_hz";
  }
  const std::string columns_problem = ParseColumnSpec(columns, nullptr);
  if (!columns_problem.empty()) return "columns: " + columns_problem;
  return "";
}

std::string LogLayout::Describe() const {
  std::string out;
  auto add = [&](const char* key, int column) {
    if (column < 0) return;
    if (!out.empty()) out += ", ";
    const std::string name =
        column < static_cast<int>(column_names.size()) ? column_names[column] : "";
    out += header_line > 0 ? fmt::format("{} = '{}' (index {})", key, name, column)
                           : fmt::format("{} = index {}", key, column);
  };
  add("t", time_column);
  add("ax", accel_columns[0]);
  add("ay", accel_columns[1]);
  add("az", accel_columns[2]);
  add("gx", gyro_columns[0]);
  add("gy", gyro_columns[1]);
  add("gz", gyro_columns[2]);
  return out;
}

namespace {

void ThrowIfInvalid(const LogOptions& options) {
  const std::string problem = options.Validate();
  if (!problem.empty()) throw Error(ErrorKind::kOption, "log options: " + problem);
}

// A text log's one time is its time column: no receive time to choose.
void RefuseReceiveTime(const std::string& path, const LogOptions& options) {
  if (options.recording_time == RecordingTime::kHeader) return;
  throw Error(ErrorKind::kOption,
              path +
                  ": a text log has one time, its time column; the receive time is "
                  "a recording's (ROS bag, MCAP)",
              logio::Give({{Option::kLogRecordingTime, "header"}}));
}

}  // namespace

// ---------------------------------------------------------------------------
// LogScanner: line by line, each line's bytes kept.

struct LogScanner::Impl {
  Impl(const std::string& path, const LogOptions& options, bool parse_gyro)
      : file(path),
        reader(&file),
        detected(logio::DetectLayout(
            reader.head(), file.eof(), file.source(), options, parse_gyro)),
        parser(detected.layout, detected.roles, options.units),
        progress(options.progress, file.size()) {
    reader.Skip(detected.bom_bytes);
    progress.Update(reader.bytes_read(), file.eof());
  }

  // Not data: the header, skipped boot text, comments and blank lines.
  bool IsOther(std::string_view text) const {
    const std::size_t line = reader.line_number();
    return line == detected.layout.header_line || line <= detected.skipped_lines ||
           logio::IsCommentOrBlank(text);
  }

  logio::LogFile file;
  logio::LineReader reader;
  logio::DetectedLayout detected;
  logio::RowParser parser;
  logio::ProgressReporter progress;
  std::size_t data_rows = 0;
};

LogScanner::LogScanner(const std::string& path,
                       const LogOptions& options,
                       bool parse_gyro) {
  ThrowIfInvalid(options);
  if (IsBag(path)) {
    throw Error(ErrorKind::kInput,
                path +
                    ": a robotics recording (ROS bag or MCAP) is read, not rewritten "
                    "line by line; only text logs are");
  }
  RefuseReceiveTime(path, options);
  impl_ = std::make_unique<Impl>(path, options, parse_gyro);
}

LogScanner::~LogScanner() = default;

const LogLayout& LogScanner::layout() const { return impl_->detected.layout; }
const std::string& LogScanner::source() const { return impl_->file.source(); }
const std::vector<std::string>& LogScanner::warnings() const {
  return impl_->detected.warnings;
}
std::uint64_t LogScanner::bytes_read() const { return impl_->reader.consumed(); }
std::uint64_t LogScanner::total_bytes() const { return impl_->file.size(); }

bool LogScanner::Next(LogLine* line) {
  Impl& s = *impl_;
  logio::CutOffLine cut_off;  // fatal unless nothing but blank lines follows
  std::string_view text;
  std::string_view eol;
  while (s.reader.Next(&text, &eol)) {
    s.progress.Update(s.reader.bytes_read(), s.file.eof());
    const bool other = s.IsOther(text);
    if (cut_off.held()) {
      if (other && logio::Trim(text).empty()) continue;
      cut_off.Throw(s.file.source());
    }
    line->text = text;
    line->eol = eol;
    line->line_number = s.reader.line_number();
    line->is_data = !other;
    if (other) return true;
    if (s.detected.layout.time_column < 0) {
      line->time_raw = static_cast<double>(s.data_rows);
    }
    logio::RowFailure why;
    if (s.parser.Parse(text, line, &why)) {
      ++s.data_rows;
      return true;
    }
    cut_off.Hold(s.reader.line_number(), s.parser.Problem(text, why));
  }
  if (cut_off.held()) s.detected.warnings.push_back(cut_off.Warning(s.file.source()));
  return false;
}

// ---------------------------------------------------------------------------
// ReadLog and ReadLogRows: the whole log, parsed on two threads, either held
// or handed over chunk by chunk.

namespace {

// The one code path of both: `*rec` gets the rows (all of them, or with
// `consume` each chunk's in turn) and, at the end, the warnings.
LogStreamSummary ReadRows(const std::string& path,
                          const LogOptions& options,
                          Recording* rec,
                          std::function<void(const Recording&)> consume) {
  ThrowIfInvalid(options);
  if (IsBag(path)) return logio::ReadBagRows(path, options, rec, std::move(consume));
  RefuseReceiveTime(path, options);
  logio::LogFile file(path);
  logio::PageBuffer head_bytes(logio::kChunkBytes);
  std::string read_error;
  const std::string_view head(
      head_bytes.data(),
      file.Read(head_bytes.data(), logio::kChunkBytes, /*fill=*/true, &read_error));
  if (!read_error.empty()) throw Error(ErrorKind::kIo, read_error);
  const logio::DetectedLayout detected = logio::DetectLayout(head,
                                                             file.eof(),
                                                             file.source(),
                                                             options,
                                                             /*parse_gyro=*/true);
  const LogLayout& layout = detected.layout;
  const logio::RowParser parser(layout, detected.roles, options.units);

  rec->units = options.units;
  rec->source = file.source();
  if (options.gyro_in_counts) rec->gyro_units = GyroUnits::kCounts;
  rec->gyro_log_units = options.gyro_units();
  logio::RowConversion conversion;
  conversion.parser = &parser;
  conversion.time_scale = layout.seconds_per_time_unit;
  conversion.gyro_scale =
      options.gyro_in_dps && !options.gyro_in_counts ? std::numbers::pi / 180.0 : 1.0;
  conversion.index_time = layout.time_column < 0;
  conversion.gyro = layout.has_gyro();
  conversion.header_line =
      layout.header_line > 0 ? layout.header_line - detected.skipped_lines : 0;

  const std::size_t start = std::max(detected.bom_bytes, detected.skipped_bytes);
  for (std::size_t line = 0; line < conversion.header_line; ++line) {
    const std::size_t nl = head.find('\n', start + conversion.header_end);
    conversion.header_end =
        nl == std::string_view::npos ? head.size() - start : nl + 1 - start;
  }
  logio::ProgressReporter progress(options.progress, file.size());
  logio::RowSink sink(rec,
                      layout.seconds_per_time_unit,
                      conversion.index_time,
                      detected.skipped_lines,
                      file.size());
  if (consume) sink.StreamTo(std::move(consume));
  // A file is read again from where the rows start rather than from the
  // head: held while the whole log is read, the head's mebibyte would sit
  // beside the rows at the peak. Standard input can only go on from it.
  std::string_view first_bytes = head.substr(start);
  if (file.Seek(start)) {
    first_bytes = {};
    head_bytes.Release();
  }
  {
    logio::ChunkPipeline pipeline(&file, first_bytes, conversion);
    while (const logio::ChunkRows* chunk = pipeline.Next()) {
      sink.Append(*chunk);
      pipeline.Release();
      progress.Update(start + pipeline.consumed());
    }
  }
  progress.Finish();
  rec->warnings = detected.warnings;
  sink.Finish(layout.header_line > 0);

  LogStreamSummary summary;
  summary.source = rec->source;
  summary.rows = sink.rows();
  summary.first_time_s = sink.first_time_s();
  summary.last_time_s = sink.last_time_s();
  summary.has_gyro = layout.has_gyro();
  return summary;
}

}  // namespace

Recording ReadLog(const std::string& path, const LogOptions& options) {
  Recording rec;
  ReadRows(path, options, &rec, nullptr);
  return rec;
}

LogStreamSummary ReadLogRows(const std::string& path,
                             const LogOptions& options,
                             const std::function<void(const Recording& rows)>& consume) {
  Recording rows;
  // Without a consumer the rows are still streamed (and dropped), never held.
  std::function<void(const Recording&)> hand_over = consume;
  if (!hand_over) hand_over = [](const Recording&) {};
  LogStreamSummary summary = ReadRows(path, options, &rows, std::move(hand_over));
  summary.warnings = std::move(rows.warnings);
  return summary;
}

}  // namespace mpcal
