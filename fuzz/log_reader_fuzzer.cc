// libFuzzer target for the log reader (ReadLog and LogScanner).
//
// The input's first byte picks the options (time unit, rate, entry point,
// an explicit column mapping taken from the input's first line; see
// log_reader_input.h); the rest is the log. The log goes through an in-memory file
// (memfd) opened by its /proc path, so that the reader runs exactly as on a file from
// disk, including stat, the regular-file size and chunked read(2), without touching the
// disk. Any outcome but success or mpcal::Error is a finding: an uncaught exception of
// another type, a sanitizer report, or a Recording that breaks its documented invariants
// (finite values, strictly increasing time).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "log_reader_input.h"
#include "memory_file.h"
#include "mpcal/error.h"
#include "mpcal/log_reader.h"

using mpcal::fuzz::Check;

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return 0;
  const mpcal::fuzz::LogReaderInput in = mpcal::fuzz::DecodeLogReaderInput(data, size);
  const std::string_view rest = in.log;
  const mpcal::LogOptions& options = in.options;

  const std::string path = mpcal::fuzz::WriteMemoryFile(rest.data(), rest.size());

  try {
    if (in.use_scanner) {
      mpcal::LogScanner scanner(path, options, in.scanner_parses_gyro);
      mpcal::LogLine line;
      std::size_t previous_line = 0;
      while (scanner.Next(&line)) {
        Check(line.line_number > previous_line, "line numbers increase");
        previous_line = line.line_number;
        if (!line.is_data) continue;
        for (const auto& [first, second] : line.accel_span) {
          Check(first <= second && second <= line.text.size(),
                "accel span inside the line");
        }
        Check(line.accel.allFinite() && std::isfinite(line.time_raw), "finite data line");
      }
      Check(scanner.bytes_read() <= rest.size(), "bytes read within the input");
    } else {
      const mpcal::Recording rec = mpcal::ReadLog(path, options);
      Check(!rec.empty(), "a recording has rows");
      Check(rec.accel.size() == rec.size(), "one reading per time");
      Check(rec.gyro_radps.empty() || rec.gyro_radps.size() == rec.size(), "gyro size");
      for (std::size_t i = 0; i < rec.size(); ++i) {
        Check(std::isfinite(rec.time_s[i]) && rec.accel[i].allFinite(), "finite values");
        if (i > 0) Check(rec.time_s[i] > rec.time_s[i - 1], "time strictly increasing");
      }
      for (const auto& g : rec.gyro_radps) Check(g.allFinite(), "finite gyro");
    }
  } catch (const mpcal::Error&) {
    // The documented way to reject an input.
  }
  return 0;
}
