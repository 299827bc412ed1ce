#include "realtime_output.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <thread>

#include <fmt/format.h>

#include "mpcal/error.h"

namespace mpcal::cli {
namespace {

// Lines due within this of each other go out in one write.
constexpr std::chrono::milliseconds kBatch{2};

// Writes all of [data, data + size); false on EPIPE.
bool WriteAll(int fd, const std::string& path, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      if (errno == EPIPE) return false;
      throw Error(ErrorKind::kIo,
                  fmt::format("cannot write '{}': {}",
                              path == "-" ? "standard output" : path,
                              std::strerror(errno)));
    }
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

int OpenOutput(const std::string& path) {
  if (path == "-") return STDOUT_FILENO;
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
  if (fd < 0) {
    throw Error(ErrorKind::kIo,
                fmt::format("cannot write '{}': {}", path, std::strerror(errno)));
  }
  return fd;
}

}  // namespace

bool WriteAtSensorPace(const std::string& path,
                       std::string_view csv,
                       const std::vector<double>& time_s,
                       double speed) {
  // A reader that quits is the end of the session, not a crash: EPIPE.
  std::signal(SIGPIPE, SIG_IGN);
  // Where each line ends; the rows are the last time_s.size() lines.
  std::vector<std::size_t> ends;
  for (std::size_t i = 0; i < csv.size(); ++i) {
    if (csv[i] == '\n') ends.push_back(i + 1);
  }
  if (ends.size() < time_s.size()) {
    throw Error(ErrorKind::kInput, "the log has fewer lines than rows");
  }
  const std::size_t header_lines = ends.size() - time_s.size();
  const int fd = OpenOutput(path);
  struct Closer {
    int fd;
    ~Closer() {
      if (fd != STDOUT_FILENO) ::close(fd);
    }
  } closer{fd};
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  std::size_t written = 0;  // bytes
  std::size_t row = 0;      // rows written
  while (row < time_s.size() || written < csv.size()) {
    const double elapsed_s = std::chrono::duration<double>(Clock::now() - start).count();
    const double due_s = time_s.empty() ? 0.0 : time_s.front() + elapsed_s * speed;
    while (row < time_s.size() && time_s[row] <= due_s) ++row;
    const std::size_t upto = row == time_s.size()      ? csv.size()
                             : header_lines + row == 0 ? 0
                                                       : ends[header_lines + row - 1];
    if (upto > written) {
      if (!WriteAll(fd, path, csv.data() + written, upto - written)) return false;
      written = upto;
    }
    if (row == time_s.size()) break;
    const auto next =
        start + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(
                    (time_s[row] - time_s.front()) / speed));
    std::this_thread::sleep_until(std::max(next, Clock::now() + kBatch));
  }
  return true;
}

}  // namespace mpcal::cli
