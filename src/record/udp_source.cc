// A UDP port ("udp:PORT", or "udp:ADDRESS:PORT" to listen on one address):
// a logger that sends its lines as datagrams, each holding whole lines. A
// datagram that does not end its last line is given the line end, so that
// no line spans two datagrams. UDP has no end: a session over UDP ends by
// its command, or by the timeout when the sender goes quiet.
#include <netdb.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <memory>

#include <fmt/format.h>

#include "mpcal/error.h"
#include "poll_source.h"
#include "sources.h"

namespace mpcal::record {
namespace {

constexpr std::size_t kMaxDatagramBytes = 65536;

class UdpSource final : public PollSource {
 public:
  UdpSource(std::string source, int fd, double timeout_s)
      : PollSource(std::move(source), fd, /*owns_fd=*/true, timeout_s) {}

 protected:
  bool Receive(std::string* out) override {
    const std::size_t before = out->size();
    out->resize(before + kMaxDatagramBytes);
    const ssize_t n = ::recv(fd(), out->data() + before, kMaxDatagramBytes, 0);
    const int error_number = errno;
    out->resize(before + static_cast<std::size_t>(n > 0 ? n : 0));
    if (n > 0 && out->back() != '\n') out->push_back('\n');
    if (n >= 0 || error_number == EINTR || error_number == EAGAIN ||
        error_number == ECONNREFUSED) {
      return true;
    }
    ThrowIo("receiving failed", error_number);
  }
  std::string StoppedHint() const override {
    return "is the logger still sending to this port (its address and port, a "
           "firewall)?";
  }
};

// The port actually bound (the one asked for, or the system's pick for 0).
std::string BoundPort(int fd) {
  sockaddr_storage addr{};
  socklen_t len = sizeof(addr);
  if (::getsockname(fd, reinterpret_cast<sockaddr*>(&addr), &len) < 0) return "";
  if (addr.ss_family == AF_INET6) {
    return std::to_string(ntohs(reinterpret_cast<const sockaddr_in6*>(&addr)->sin6_port));
  }
  return std::to_string(ntohs(reinterpret_cast<const sockaddr_in*>(&addr)->sin_port));
}

// Binds the first address `host` (empty: every address of `family`) gives
// for `port`; the socket, or -1 with `*error_number` set.
int BindFirst(const std::string& host,
              const std::string& port,
              int family,
              int* error_number) {
  addrinfo hints{};
  hints.ai_family = family;
  hints.ai_socktype = SOCK_DGRAM;
  hints.ai_flags = AI_PASSIVE;
  addrinfo* found = nullptr;
  const int gai =
      ::getaddrinfo(host.empty() ? nullptr : host.c_str(), port.c_str(), &hints, &found);
  if (gai != 0) {
    *error_number = -gai;  // negative: a resolver error (gai_strerror)
    return -1;
  }
  int bound = -1;
  for (const addrinfo* a = found; a != nullptr && bound < 0; a = a->ai_next) {
    const int fd = ::socket(a->ai_family, a->ai_socktype | SOCK_CLOEXEC, a->ai_protocol);
    if (fd < 0) {
      *error_number = errno;
      continue;
    }
    if (a->ai_family == AF_INET6 && host.empty()) {
      const int off = 0;  // IPv4 senders too
      ::setsockopt(fd, IPPROTO_IPV6, IPV6_V6ONLY, &off, sizeof(off));
    }
    if (::bind(fd, a->ai_addr, a->ai_addrlen) == 0) {
      bound = fd;
    } else {
      *error_number = errno;
      ::close(fd);
    }
  }
  ::freeaddrinfo(found);
  return bound;
}

}  // namespace

std::unique_ptr<LiveSource> OpenUdp(const LiveSourceOptions& options) {
  const std::string& spec = options.spec;
  const HostPort hp = SplitHostPort(spec, spec.substr(4), /*allow_any_port=*/true);
  int error_number = 0;
  // Every address: IPv6 and IPv4 on one socket, or IPv4 alone where the
  // system has no IPv6.
  int fd =
      BindFirst(hp.host, hp.port, hp.host.empty() ? AF_INET6 : AF_UNSPEC, &error_number);
  if (fd < 0 && hp.host.empty() && error_number != EADDRINUSE && error_number != EACCES) {
    fd = BindFirst(hp.host, hp.port, AF_INET, &error_number);
  }
  if (fd >= 0) {
    const std::string name =
        "udp:" + (hp.host.empty() ? "" : hp.host + ":") + BoundPort(fd);
    return std::make_unique<UdpSource>(name, fd, options.timeout_s);
  }
  if (error_number < 0) {
    throw Error(ErrorKind::kIo,
                fmt::format("{}: cannot listen on '{}' ({}); give an address of this "
                            "machine, or none",
                            spec,
                            hp.host,
                            ::gai_strerror(-error_number)));
  }
  if (error_number == EADDRINUSE) {
    throw Error(ErrorKind::kIo,
                fmt::format("{}: port {} is in use by another program; stop it, or "
                            "have the logger send to another port",
                            spec,
                            hp.port));
  }
  if (error_number == EACCES) {
    throw Error(ErrorKind::kIo,
                fmt::format("{}: port {} needs privileges (ports below 1024); use a "
                            "port of 1024 or above",
                            spec,
                            hp.port));
  }
  throw Error(ErrorKind::kIo,
              fmt::format("{}: cannot listen on port {} ({})",
                          spec,
                          hp.port,
                          std::strerror(error_number)));
}

}  // namespace mpcal::record
