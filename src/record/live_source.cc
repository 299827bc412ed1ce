// OpenLiveSource: the spec says which kind of source; the options are
// checked here once for all of them. Standard input is the simplest source:
// the descriptor is there already and stays open after the session.
#include "mpcal/live_source.h"

#include <unistd.h>

#include <charconv>
#include <cmath>
#include <string_view>

#include <fmt/format.h>

#include "mpcal/error.h"
#include "poll_source.h"
#include "sources.h"

namespace mpcal {

LiveSource::~LiveSource() = default;

std::string LiveSourceOptions::Validate() const {
  if (spec.empty())
    return "spec is empty: give '-', a serial port, tcp:HOST:PORT or udp:PORT";
  if (baud <= 0) return fmt::format("baud must be a positive rate, got {}", baud);
  if (!std::isfinite(timeout_s) || timeout_s <= 0.0) {
    return fmt::format("timeout_s must be a positive number of seconds, got {}",
                       timeout_s);
  }
  return "";
}

LiveSourceKind KindOfLiveSource(const std::string& spec) {
  if (spec.empty()) throw Error(ErrorKind::kOption, "the live source is empty");
  if (spec == "-") return LiveSourceKind::kStdin;
  const std::string_view s(spec);
  if (s.starts_with("tcp:")) {
    record::SplitHostPort(spec, spec.substr(4), /*allow_any_port=*/false);
    return LiveSourceKind::kTcp;
  }
  if (s.starts_with("udp:")) {
    record::SplitHostPort(spec, spec.substr(4), /*allow_any_port=*/true);
    return LiveSourceKind::kUdp;
  }
  return LiveSourceKind::kSerial;
}

std::unique_ptr<LiveSource> OpenLiveSource(const LiveSourceOptions& options) {
  const std::string problem = options.Validate();
  if (!problem.empty()) throw Error(ErrorKind::kOption, "live source: " + problem);
  switch (KindOfLiveSource(options.spec)) {
    case LiveSourceKind::kStdin:
      return record::OpenStdin(options);
    case LiveSourceKind::kTcp:
      return record::OpenTcp(options);
    case LiveSourceKind::kUdp:
      return record::OpenUdp(options);
    case LiveSourceKind::kSerial:
      return record::OpenSerial(options);
  }
  return nullptr;
}

namespace record {

HostPort SplitHostPort(const std::string& spec,
                       const std::string& rest,
                       bool allow_any_port) {
  HostPort hp;
  std::string_view r(rest);
  const std::size_t colon = r.rfind(':');
  if (colon != std::string_view::npos) {
    hp.host = std::string(r.substr(0, colon));
    r = r.substr(colon + 1);
  }
  if (hp.host.size() >= 2 && hp.host.front() == '[' && hp.host.back() == ']') {
    hp.host = hp.host.substr(1, hp.host.size() - 2);
  }
  unsigned port = 0;
  const auto [end, ec] = std::from_chars(r.data(), r.data() + r.size(), port);
  const bool number = !r.empty() && ec == std::errc() && end == r.data() + r.size();
  if (!number || port > 65535 || (port == 0 && !allow_any_port)) {
    throw Error(ErrorKind::kOption,
                fmt::format("'{}': expected a port number from 1 to 65535 after the last "
                            "':', as in tcp:192.168.4.1:5000 or udp:5000",
                            spec));
  }
  hp.port = std::to_string(port);
  return hp;
}

namespace {

class StdinSource final : public PollSource {
 public:
  explicit StdinSource(double timeout_s)
      : PollSource("<stdin>", STDIN_FILENO, /*owns_fd=*/false, timeout_s) {}

 protected:
  std::string StoppedHint() const override {
    return "is the program writing into the pipe still running, and does it flush "
           "each line?";
  }
};

}  // namespace

std::unique_ptr<LiveSource> OpenStdin(const LiveSourceOptions& options) {
  return std::make_unique<StdinSource>(options.timeout_s);
}

}  // namespace record
}  // namespace mpcal
