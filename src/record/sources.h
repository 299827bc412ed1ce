// The kinds of live source, one file each; OpenLiveSource (live_source.cc)
// picks one by the spec. Private to src/record.
#pragma once

#include <memory>
#include <string>

#include "mpcal/live_source.h"

namespace mpcal::record {

/// "HOST:PORT" (IPv6 as "[::1]:PORT") split; the port 1..65535 (0 too when
/// `allow_any_port`). \throws mpcal::Error (kOption) naming `spec`.
struct HostPort {
  std::string host;
  std::string port;
};
HostPort SplitHostPort(const std::string& spec,
                       const std::string& rest,
                       bool allow_any_port);

std::unique_ptr<LiveSource> OpenStdin(const LiveSourceOptions& options);
std::unique_ptr<LiveSource> OpenTcp(const LiveSourceOptions& options);
std::unique_ptr<LiveSource> OpenUdp(const LiveSourceOptions& options);
std::unique_ptr<LiveSource> OpenSerial(const LiveSourceOptions& options);

}  // namespace mpcal::record
