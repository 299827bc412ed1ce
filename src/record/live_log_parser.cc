// A live stream's lines through the log reader's own parts: layout
// detection (io/log_layout.h) on the first lines as they arrive, then each
// whole line through the chunk parser (io/chunk_source.h) and the row sink
// (io/row_sink.h), one line at a time, so that the rules (duplicates, time
// going back, a malformed line with data after it) and their messages are
// ReadLog's, and a line an Error refuses is known exactly (it is not written
// to the session).
#include <algorithm>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "io/chunk_source.h"
#include "io/log_layout.h"
#include "io/row_parser.h"
#include "io/row_sink.h"
#include "mpcal/error.h"
#include "mpcal/live_source.h"

namespace mpcal {
namespace {

// The layout is found once this many data rows came (a logger's first half
// second at 100 Hz; the delimiter is sniffed from 50 lines), or this many
// lines, or this many bytes (a stream that is not IMU lines ends in
// detection's own error, with bounded memory).
constexpr std::size_t kDetectRows = 50;
constexpr std::size_t kDetectLines = 500;
constexpr std::size_t kDetectBytes = std::size_t{1} << 16;

// A header for a log that has none: each mapped column named by its key
// (t, ax, ..., gz), the others "c<N>", so that the session file reads to
// the same columns without a mapping.
std::string HeaderFor(const logio::DetectedLayout& d, std::size_t data_columns) {
  const LogLayout& layout = d.layout;
  std::vector<std::string> names;
  for (std::size_t c = 0; c < data_columns; ++c) {
    const auto column = static_cast<int>(c);
    std::string name = fmt::format("c{}", c);
    if (column == layout.time_column) name = "t";
    for (int i = 0; i < 3; ++i) {
      if (column == layout.accel_columns[i]) name = logio::kRoleKeys[logio::kAx + i];
      if (column == layout.gyro_columns[i]) name = logio::kRoleKeys[logio::kGx + i];
    }
    names.push_back(std::move(name));
  }
  const std::string delimiter(1, layout.delimiter);
  return fmt::format("{}\n", fmt::join(names, delimiter));
}

}  // namespace

struct LiveLogParser::Impl {
  Impl(const LogOptions& opts, std::string name)
      : options(opts), source(std::move(name)) {
    const std::string problem = options.Validate();
    if (!problem.empty()) throw Error(ErrorKind::kOption, "log options: " + problem);
    if (options.recording_time != RecordingTime::kHeader) {
      throw Error(ErrorKind::kOption,
                  source +
                      ": a live stream has one time, its time column; the receive "
                      "time is a recording's (ROS bag, MCAP)");
    }
    staging.units = options.units;
    staging.source = source;
    if (options.gyro_in_counts) staging.gyro_units = GyroUnits::kCounts;
    staging.gyro_log_units = options.gyro_units();
  }

  bool ReadyToDetect();
  void Detect(bool at_end);
  void ParseLines(std::string_view text, bool at_end);
  void ParseLine(std::string_view line);
  void TakeRows(const Recording& rows);
  void PrepareRows(Recording* rows) const;

  LogOptions options;
  std::string source;
  std::string head;              // every byte until the layout is known
  std::size_t head_scanned = 0;  // bytes of `head` counted below
  std::size_t head_rows = 0;     // number rows among them
  std::size_t head_lines = 0;    // lines among them
  std::size_t detect_end = 0;    // the layout is found from head[0, detect_end)
  std::string pending;           // after: the incomplete last line
  std::optional<logio::DetectedLayout> detected;
  std::optional<logio::RowParser> parser;
  logio::RowConversion conversion;
  std::optional<logio::RowSink> sink;
  std::size_t header_line = 0;  // after the skipped lines; 0 for none
  std::size_t line = 0;         // lines parsed after the skipped ones
  logio::ChunkRows chunk;
  Recording staging;         // the sink's row buffer
  Recording* out = nullptr;  // the caller's, during Feed and Finish
  std::string session;       // text for the session file, not yet taken
  std::vector<std::string> warnings;
  bool finished = false;
};

void LiveLogParser::Impl::PrepareRows(Recording* rows) const {
  rows->units = staging.units;
  rows->gyro_units = staging.gyro_units;
  rows->gyro_log_units = staging.gyro_log_units;
  if (rows->source.empty()) rows->source = source;
}

void LiveLogParser::Impl::TakeRows(const Recording& rows) {
  out->time_s.insert(out->time_s.end(), rows.time_s.begin(), rows.time_s.end());
  out->accel.insert(out->accel.end(), rows.accel.begin(), rows.accel.end());
  out->gyro_radps.insert(
      out->gyro_radps.end(), rows.gyro_radps.begin(), rows.gyro_radps.end());
}

// Counts the whole lines that came since the last look, in order, and
// marks where the layout is found from: after the line that makes
// kDetectRows data rows or kDetectLines lines, or at kDetectBytes. The mark
// depends on the bytes alone, never on the pieces they came in.
bool LiveLogParser::Impl::ReadyToDetect() {
  while (head_scanned < head.size()) {
    const std::size_t nl = head.find('\n', head_scanned);
    if (nl == std::string::npos || nl + 1 > kDetectBytes) {
      if (head.size() < kDetectBytes) return false;
      detect_end = kDetectBytes;
      return true;
    }
    ++head_lines;
    if (logio::IsNumberRow(
            std::string_view(head).substr(head_scanned, nl - head_scanned))) {
      ++head_rows;
    }
    head_scanned = nl + 1;
    if (head_rows >= kDetectRows || head_lines >= kDetectLines) {
      detect_end = head_scanned;
      return true;
    }
  }
  return false;
}

void LiveLogParser::Impl::Detect(bool at_end) {
  if (at_end) detect_end = head.size();
  detected.emplace(logio::DetectLayout(std::string_view(head).substr(0, detect_end),
                                       at_end,
                                       source,
                                       options,
                                       /*parse_gyro=*/true));
  const LogLayout& layout = detected->layout;
  parser.emplace(layout, detected->roles, options.units);
  conversion.parser = &*parser;
  conversion.time_scale = layout.seconds_per_time_unit;
  conversion.gyro_scale =
      options.gyro_in_dps && !options.gyro_in_counts ? std::numbers::pi / 180.0 : 1.0;
  conversion.index_time = layout.time_column < 0;
  conversion.gyro = layout.has_gyro();
  header_line = layout.header_line > 0 ? layout.header_line - detected->skipped_lines : 0;
  sink.emplace(&staging,
               layout.seconds_per_time_unit,
               conversion.index_time,
               detected->skipped_lines,
               /*total_bytes=*/0);
  sink->StreamTo([this](const Recording& rows) { TakeRows(rows); });
  warnings = detected->warnings;
  const std::size_t start = std::max(detected->bom_bytes, detected->skipped_bytes);
  if (header_line == 0) {
    const std::size_t columns = std::max<std::size_t>(
        layout.column_names.size(), static_cast<std::size_t>(layout.min_columns));
    session += HeaderFor(*detected, columns);
  }
  std::string bytes = std::move(head);
  head.clear();
  head.shrink_to_fit();
  ParseLines(std::string_view(bytes).substr(std::min(start, bytes.size())), at_end);
}

// Whole lines of `text`, one by one; the rest kept in `pending` (or, at the
// end, parsed as the last line).
void LiveLogParser::Impl::ParseLines(std::string_view text, bool at_end) {
  // A line longer than any log's: the same error whether it came whole or
  // is still coming.
  auto check_length = [this](std::size_t bytes) {
    if (bytes > logio::kMaxLineBytes) {
      logio::ThrowLineTooLong(source, detected->skipped_lines + line + 1);
    }
  };
  std::size_t pos = 0;
  while (pos < text.size()) {
    const std::size_t nl = text.find('\n', pos);
    if (nl == std::string_view::npos) break;
    check_length(nl - pos);
    ParseLine(text.substr(pos, nl + 1 - pos));
    pos = nl + 1;
  }
  check_length(text.size() - pos);
  pending.assign(text.substr(pos));
  if (at_end && !pending.empty()) {
    const std::string last = std::move(pending);
    pending.clear();
    ParseLine(last);
  }
}

// One line (with its end, if it has one): its rows handed over by the sink,
// its bytes to the session unless the sink refused it.
void LiveLogParser::Impl::ParseLine(std::string_view text) {
  ++line;
  logio::ParseChunkLines(conversion, text, line == header_line ? 1 : 0, &chunk);
  sink->Append(chunk);
  session.append(text);
}

LiveLogParser::LiveLogParser(const LogOptions& options, std::string source_name)
    : impl_(std::make_unique<Impl>(options, std::move(source_name))) {}

LiveLogParser::~LiveLogParser() = default;

void LiveLogParser::Feed(std::string_view bytes, Recording* rows) {
  Impl& s = *impl_;
  if (s.finished) {
    throw Error(ErrorKind::kOption, s.source + ": bytes fed after the end of the stream");
  }
  s.PrepareRows(rows);
  s.out = rows;
  if (!s.detected) {
    s.head.append(bytes);
    if (s.ReadyToDetect()) s.Detect(false);
    return;
  }
  if (s.pending.empty()) {
    s.ParseLines(bytes, false);
    return;
  }
  // The kept line's start and what came now: parsed from one buffer.
  std::string joined = std::move(s.pending);
  joined.append(bytes);
  s.ParseLines(joined, false);
}

void LiveLogParser::Finish(Recording* rows) {
  Impl& s = *impl_;
  if (s.finished) return;
  s.finished = true;
  s.PrepareRows(rows);
  s.out = rows;
  if (!s.detected) {
    s.Detect(true);
  } else {
    const std::string last = std::move(s.pending);
    s.pending.clear();
    s.ParseLines(last, true);
  }
  s.staging.warnings.clear();
  s.sink->Finish(s.detected->layout.header_line > 0);
  for (auto& w : s.staging.warnings) s.warnings.push_back(std::move(w));
  s.staging.warnings.clear();
}

bool LiveLogParser::layout_known() const { return impl_->detected.has_value(); }

const LogLayout& LiveLogParser::layout() const {
  if (!impl_->detected) {
    throw Error(ErrorKind::kOption, impl_->source + ": the layout is not known yet");
  }
  return impl_->detected->layout;
}

std::size_t LiveLogParser::skipped_lines() const {
  return impl_->detected ? impl_->detected->skipped_lines : 0;
}

std::size_t LiveLogParser::rows() const { return impl_->sink ? impl_->sink->rows() : 0; }

const std::vector<std::string>& LiveLogParser::warnings() const {
  return impl_->warnings;
}

std::string LiveLogParser::TakeSessionText() {
  std::string text = std::move(impl_->session);
  impl_->session.clear();
  return text;
}

}  // namespace mpcal
