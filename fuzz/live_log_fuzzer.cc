// libFuzzer target for the live stream's parser (LiveLogParser).
//
// The input's first byte picks the options as for the log reader
// (log_reader_input.h; its reader and scanner bits unused); the next two
// bytes, a point where the stream is cut in two; the rest is the stream.
// The stream is parsed whole (one piece) and cut at that point, and byte by
// byte up to it: the outcomes must be the same (the same rows and session
// text, or the same mpcal::Error after the same rows). Any other outcome is
// a finding: an exception of another type, a sanitizer report, pieces that
// change the result, or rows that break a Recording's invariants.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

#include "log_reader_input.h"
#include "mpcal/error.h"
#include "mpcal/live_source.h"

namespace {

struct Outcome {
  mpcal::Recording rows;
  std::string session;
  std::string error;  // empty: no error
  bool layout_known = false;
  std::size_t skipped = 0;
};

void Check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "invariant broken: %s\n", what);
    std::abort();
  }
}

// The stream fed in pieces ending at `cuts`, then the rest, then its end.
Outcome Parse(std::string_view stream,
              const mpcal::LogOptions& options,
              const std::vector<std::size_t>& cuts) {
  Outcome out;
  mpcal::LiveLogParser parser(options, "live");
  try {
    std::size_t from = 0;
    for (const std::size_t cut : cuts) {
      parser.Feed(stream.substr(from, cut - from), &out.rows);
      out.session += parser.TakeSessionText();
      from = cut;
    }
    parser.Feed(stream.substr(from), &out.rows);
    out.session += parser.TakeSessionText();
    parser.Finish(&out.rows);
  } catch (const mpcal::Error& e) {
    out.error = e.what();
  }
  out.session += parser.TakeSessionText();
  out.layout_known = parser.layout_known();
  out.skipped = parser.skipped_lines();
  return out;
}

bool SameRows(const mpcal::Recording& a, const mpcal::Recording& b) {
  if (a.time_s.size() != b.time_s.size() || a.accel.size() != b.accel.size() ||
      a.gyro_radps.size() != b.gyro_radps.size()) {
    return false;
  }
  for (std::size_t i = 0; i < a.time_s.size(); ++i) {
    if (a.time_s[i] != b.time_s[i] || a.accel[i] != b.accel[i]) return false;
  }
  for (std::size_t i = 0; i < a.gyro_radps.size(); ++i) {
    if (a.gyro_radps[i] != b.gyro_radps[i]) return false;
  }
  return true;
}

void CheckSame(const Outcome& whole, const Outcome& cut) {
  Check(cut.error == whole.error, "the same error whatever the pieces");
  Check(SameRows(cut.rows, whole.rows), "the same rows whatever the pieces");
  Check(cut.session == whole.session, "the same session text whatever the pieces");
  Check(cut.layout_known == whole.layout_known && cut.skipped == whole.skipped,
        "the same layout whatever the pieces");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size < 3) return 0;
  const mpcal::fuzz::LogReaderInput in = mpcal::fuzz::DecodeLogReaderInput(data, size);
  // DecodeLogReaderInput took the first byte (and perhaps a mapping line):
  // the split point is the next two bytes of what is left.
  std::string_view rest = in.log;
  if (rest.size() < 2) return 0;
  const std::size_t split_at =
      (static_cast<unsigned char>(rest[0]) | (static_cast<unsigned char>(rest[1]) << 8));
  const std::string_view stream = rest.substr(2);
  const std::size_t split = stream.empty() ? 0 : split_at % (stream.size() + 1);

  const Outcome whole = Parse(stream, in.options, {});
  const mpcal::Recording& r = whole.rows;
  Check(r.accel.size() == r.time_s.size(), "one reading per time");
  Check(r.gyro_radps.empty() || r.gyro_radps.size() == r.time_s.size(), "gyro size");
  for (std::size_t i = 0; i < r.time_s.size(); ++i) {
    Check(std::isfinite(r.time_s[i]) && r.accel[i].allFinite(), "finite values");
    if (i > 0) Check(r.time_s[i] > r.time_s[i - 1], "time strictly increasing");
  }
  CheckSame(whole, Parse(stream, in.options, {split}));
  // Byte by byte up to the point (bounded, so that a run stays fast).
  std::vector<std::size_t> bytes;
  for (std::size_t i = 1; i <= split && i <= 512; ++i) bytes.push_back(i);
  CheckSame(whole, Parse(stream, in.options, bytes));
  return 0;
}
