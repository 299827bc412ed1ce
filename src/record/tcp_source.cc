// A TCP stream ("tcp:HOST:PORT"): a logger's server (an ESP32 on Wi-Fi, a
// socat or ser2net bridge) that sends its lines to whoever connects. The
// connection is made within the timeout, address by address as the
// resolver gives them; the peer closing is the end of the stream.
#include <netdb.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>
#include <memory>

#include <fmt/format.h>

#include "mpcal/error.h"
#include "poll_source.h"
#include "sources.h"

namespace mpcal::record {
namespace {

class TcpSource final : public PollSource {
 public:
  TcpSource(std::string source, int fd, double timeout_s)
      : PollSource(std::move(source), fd, /*owns_fd=*/true, timeout_s) {}

 protected:
  std::string StoppedHint() const override {
    return "is the logger still sending (the connection is open but silent)?";
  }
};

struct AddrInfoFree {
  void operator()(addrinfo* a) const { ::freeaddrinfo(a); }
};

// Connects to one address within `wait_s`; the socket, or -1 with errno.
int ConnectOne(const addrinfo& a, double wait_s) {
  const int fd =
      ::socket(a.ai_family, a.ai_socktype | SOCK_NONBLOCK | SOCK_CLOEXEC, a.ai_protocol);
  if (fd < 0) return -1;
  int error_number = 0;
  if (::connect(fd, a.ai_addr, a.ai_addrlen) < 0) {
    error_number = errno;
    if (error_number == EINPROGRESS) {
      pollfd p{fd, POLLOUT, 0};
      int ready = 0;
      do {
        ready = ::poll(&p, 1, PollMilliseconds(wait_s));
      } while (ready < 0 && errno == EINTR);
      socklen_t len = sizeof(error_number);
      if (ready == 0) {
        error_number = ETIMEDOUT;
      } else if (ready < 0 ||
                 ::getsockopt(fd, SOL_SOCKET, SO_ERROR, &error_number, &len) < 0) {
        error_number = errno;
      }
    }
  }
  if (error_number != 0) {
    ::close(fd);
    errno = error_number;
    return -1;
  }
  return fd;
}

}  // namespace

std::unique_ptr<LiveSource> OpenTcp(const LiveSourceOptions& options) {
  const std::string& spec = options.spec;
  const HostPort hp = SplitHostPort(spec, spec.substr(4), /*allow_any_port=*/false);
  if (hp.host.empty()) {
    throw Error(ErrorKind::kOption,
                fmt::format("'{}': give the host to connect to, as in tcp:192.168.4.1:{}",
                            spec,
                            hp.port));
  }
  addrinfo hints{};
  hints.ai_family = AF_UNSPEC;
  hints.ai_socktype = SOCK_STREAM;
  addrinfo* found = nullptr;
  const int gai = ::getaddrinfo(hp.host.c_str(), hp.port.c_str(), &hints, &found);
  if (gai != 0) {
    throw Error(ErrorKind::kIo,
                fmt::format("{}: cannot find the host '{}' ({}); check its name or give "
                            "its IP address",
                            spec,
                            hp.host,
                            ::gai_strerror(gai)));
  }
  const std::unique_ptr<addrinfo, AddrInfoFree> addresses(found);
  const auto start = std::chrono::steady_clock::now();
  int error_number = ETIMEDOUT;
  for (const addrinfo* a = found; a != nullptr; a = a->ai_next) {
    const double left =
        options.timeout_s - SecondsBetween(start, std::chrono::steady_clock::now());
    if (left <= 0.0) break;
    const int fd = ConnectOne(*a, left);
    if (fd >= 0) return std::make_unique<TcpSource>(spec, fd, options.timeout_s);
    error_number = errno;
  }
  if (error_number == ECONNREFUSED) {
    throw Error(ErrorKind::kIo,
                fmt::format("{}: connection refused: nothing listens on port {} of {}; "
                            "start the logger's server, or check the port",
                            spec,
                            hp.port,
                            hp.host));
  }
  if (error_number == ETIMEDOUT) {
    throw Error(ErrorKind::kIo,
                fmt::format("{}: no connection within {:g} s: is {} up and reachable, "
                            "and port {} open?",
                            spec,
                            options.timeout_s,
                            hp.host,
                            hp.port));
  }
  throw Error(ErrorKind::kIo,
              fmt::format("{}: cannot connect ({}); check the host and port",
                          spec,
                          std::strerror(error_number)));
}

}  // namespace mpcal::record
