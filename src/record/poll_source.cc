#include "poll_source.h"

#include <poll.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <limits>
#include <utility>

#include <fmt/format.h>

#include "mpcal/error.h"

namespace mpcal::record {
namespace {

// Bytes taken from the descriptor at a time: a logger sends far less
// between two reads.
constexpr std::size_t kReadBytes = std::size_t{1} << 16;

}  // namespace

int PollMilliseconds(double s) {
  if (!(s > 0.0)) return 0;
  const double ms = std::ceil(s * 1000.0);
  return ms >= static_cast<double>(std::numeric_limits<int>::max())
             ? std::numeric_limits<int>::max()
             : static_cast<int>(ms);
}

PollSource::PollSource(std::string source, int fd, bool owns_fd, double timeout_s)
    : source_(std::move(source)),
      fd_(fd),
      owns_fd_(owns_fd),
      timeout_s_(timeout_s),
      last_byte_(std::chrono::steady_clock::now()) {}

PollSource::~PollSource() {
  if (owns_fd_ && fd_ >= 0) ::close(fd_);
}

void PollSource::ThrowIo(const std::string& what, int error_number) const {
  throw Error(ErrorKind::kIo,
              fmt::format("{}: {} ({})", source_, what, std::strerror(error_number)));
}

std::string PollSource::StoppedHint() const {
  return "is the logger still running and writing?";
}

void PollSource::ThrowStopped(double silent_s) const {
  throw Error(ErrorKind::kIo,
              fmt::format("{}: the stream stopped: no byte for {:.1f} s (the timeout is "
                          "{:g} s); {}",
                          source_,
                          silent_s,
                          timeout_s_,
                          StoppedHint()));
}

bool PollSource::Receive(std::string* out) {
  const std::size_t before = out->size();
  out->resize(before + kReadBytes);
  const ssize_t n = ::read(fd_, out->data() + before, kReadBytes);
  const int error_number = errno;
  out->resize(before + static_cast<std::size_t>(std::max<ssize_t>(n, 0)));
  if (n > 0) return true;
  if (n == 0) return false;
  if (error_number == EINTR || error_number == EAGAIN || error_number == EWOULDBLOCK) {
    return true;
  }
  // A reset by the peer of a TCP stream is its way of closing.
  if (error_number == ECONNRESET) return false;
  ThrowIo("reading failed", error_number);
}

bool PollSource::Read(std::string* out, double wait_s) {
  const auto now = std::chrono::steady_clock::now();
  const double silent_s = SecondsBetween(last_byte_, now);
  if (silent_s >= timeout_s_) ThrowStopped(silent_s);
  const double wait = std::min(std::max(wait_s, 0.0), timeout_s_ - silent_s);
  pollfd p{fd_, POLLIN, 0};
  const int ready = ::poll(&p, 1, PollMilliseconds(wait));
  if (ready < 0) {
    if (errno == EINTR) return true;  // a signal: the caller looks at its flags
    ThrowIo("waiting for data failed", errno);
  }
  if (ready == 0) {
    const double silent_now =
        SecondsBetween(last_byte_, std::chrono::steady_clock::now());
    if (silent_now >= timeout_s_) ThrowStopped(silent_now);
    return true;
  }
  if ((p.revents & POLLNVAL) != 0) ThrowIo("not an open stream", EBADF);
  const std::size_t before = out->size();
  const bool more = Receive(out);
  if (out->size() > before) {
    received_ += out->size() - before;
    last_byte_ = std::chrono::steady_clock::now();
  }
  return more;
}

}  // namespace mpcal::record
