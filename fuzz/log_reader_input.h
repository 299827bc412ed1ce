// How a fuzzer input becomes a call of the log reader: shared by the fuzz
// target and the regression test that replays the corpus (tests/io).
//
// The first byte picks the options: bits 0-2 the time unit (auto, s, ms, us,
// ns, index, auto, auto), bit 3 a rate of 100 Hz, bit 4 gyroscope in deg/s,
// bit 5 LogScanner instead of ReadLog, bit 6 the first line is the --columns
// value, bit 7 the scanner parses the gyroscope. The rest is the log.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "mpcal/log_reader.h"

namespace mpcal::fuzz {

struct LogReaderInput {
  LogOptions options;
  bool use_scanner = false;
  bool scanner_parses_gyro = false;
  std::string_view log;
};

inline LogReaderInput DecodeLogReaderInput(const std::uint8_t* data, std::size_t size) {
  LogReaderInput in;
  if (size == 0) return in;
  const std::uint8_t selector = data[0];
  std::string_view rest(reinterpret_cast<const char*>(data + 1), size - 1);
  constexpr TimeUnit kUnits[] = {TimeUnit::kAuto,
                                 TimeUnit::kSeconds,
                                 TimeUnit::kMilliseconds,
                                 TimeUnit::kMicroseconds,
                                 TimeUnit::kNanoseconds,
                                 TimeUnit::kSampleIndex,
                                 TimeUnit::kAuto,
                                 TimeUnit::kAuto};
  in.options.time_unit = kUnits[selector & 7];
  in.options.rate_hz = (selector & 8) ? 100.0 : 0.0;
  in.options.gyro_in_dps = (selector & 16) != 0;
  in.use_scanner = (selector & 32) != 0;
  in.scanner_parses_gyro = (selector & 128) != 0;
  if (selector & 64) {
    const auto nl = rest.find('\n');
    in.options.columns = std::string(rest.substr(0, nl));
    rest = nl == std::string_view::npos ? std::string_view() : rest.substr(nl + 1);
  }
  in.log = rest;
  return in;
}

}  // namespace mpcal::fuzz
