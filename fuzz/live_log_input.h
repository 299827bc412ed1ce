// How a fuzzer input becomes a live stream, and what must hold of its
// parse: shared by the fuzz target (live_log_fuzzer.cc) and the test that
// replays the corpus (tests/record).
//
// The input's first byte picks the options as for the log reader
// (log_reader_input.h; its reader and scanner bits unused); the next two
// bytes, a point where the stream is cut in two; the rest is the stream.
// The stream is parsed whole (one piece), cut at that point, and byte by
// byte up to it (at most 512 bytes): the outcomes must be the same (the same
// rows, session text and layout, or the same mpcal::Error after the same
// rows), and the rows a Recording's (finite, time strictly increasing).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "log_reader_input.h"
#include "mpcal/error.h"
#include "mpcal/live_source.h"

namespace mpcal::fuzz {

struct LiveLogOutcome {
  Recording rows;
  std::string session;
  std::string error;  // empty: no error
  bool layout_known = false;
  std::size_t skipped = 0;
};

// The stream fed in pieces ending at `cuts`, then the rest, then its end.
inline LiveLogOutcome ParseLive(std::string_view stream,
                                const LogOptions& options,
                                const std::vector<std::size_t>& cuts) {
  LiveLogOutcome out;
  std::unique_ptr<LiveLogParser> parser;
  try {
    parser = std::make_unique<LiveLogParser>(options, "live");  // options checked
    std::size_t from = 0;
    for (const std::size_t cut : cuts) {
      parser->Feed(stream.substr(from, cut - from), &out.rows);
      out.session += parser->TakeSessionText();
      from = cut;
    }
    parser->Feed(stream.substr(from), &out.rows);
    out.session += parser->TakeSessionText();
    parser->Finish(&out.rows);
  } catch (const Error& e) {
    out.error = e.what();
  }
  if (parser) {
    out.session += parser->TakeSessionText();
    out.layout_known = parser->layout_known();
    out.skipped = parser->skipped_lines();
  }
  return out;
}

inline bool SameRows(const Recording& a, const Recording& b) {
  if (a.time_s != b.time_s || a.accel.size() != b.accel.size() ||
      a.gyro_radps.size() != b.gyro_radps.size()) {
    return false;
  }
  for (std::size_t i = 0; i < a.accel.size(); ++i) {
    if (a.accel[i] != b.accel[i]) return false;
  }
  for (std::size_t i = 0; i < a.gyro_radps.size(); ++i) {
    if (a.gyro_radps[i] != b.gyro_radps[i]) return false;
  }
  return true;
}

inline std::string Differences(const LiveLogOutcome& whole, const LiveLogOutcome& cut) {
  if (cut.error != whole.error) return "the same error whatever the pieces";
  if (!SameRows(cut.rows, whole.rows)) return "the same rows whatever the pieces";
  if (cut.session != whole.session) return "the same session text whatever the pieces";
  if (cut.layout_known != whole.layout_known || cut.skipped != whole.skipped) {
    return "the same layout whatever the pieces";
  }
  return "";
}

/// "" when everything holds; otherwise the invariant broken.
inline std::string CheckLiveLogInput(const std::uint8_t* data, std::size_t size) {
  if (size < 3) return "";
  const LogReaderInput in = DecodeLogReaderInput(data, size);
  const std::string_view rest = in.log;
  if (rest.size() < 2) return "";
  const std::size_t split_at =
      static_cast<unsigned char>(rest[0]) |
      (static_cast<std::size_t>(static_cast<unsigned char>(rest[1])) << 8);
  const std::string_view stream = rest.substr(2);
  const std::size_t split = split_at % (stream.size() + 1);

  const LiveLogOutcome whole = ParseLive(stream, in.options, {});
  const Recording& r = whole.rows;
  if (r.accel.size() != r.time_s.size()) return "one reading per time";
  if (!r.gyro_radps.empty() && r.gyro_radps.size() != r.time_s.size()) return "gyro size";
  for (std::size_t i = 0; i < r.time_s.size(); ++i) {
    if (!std::isfinite(r.time_s[i]) || !r.accel[i].allFinite()) return "finite values";
    if (i > 0 && !(r.time_s[i] > r.time_s[i - 1])) return "time strictly increasing";
  }
  std::string problem = Differences(whole, ParseLive(stream, in.options, {split}));
  if (!problem.empty()) return problem + " (cut in two)";
  std::vector<std::size_t> bytes;
  for (std::size_t i = 1; i <= split && i <= 512; ++i) bytes.push_back(i);
  problem = Differences(whole, ParseLive(stream, in.options, bytes));
  if (!problem.empty()) return problem + " (byte by byte)";
  return "";
}

}  // namespace mpcal::fuzz
