#include "mpcal/text_input.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>

#include <fmt/format.h>

#include "mpcal/error.h"

namespace mpcal {
namespace {

constexpr std::size_t kTextCheckBytes = 65536;

std::string_view FileKind(mode_t mode) {
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

// The same test as the log reader's: a NUL byte, or more than 1% control
// characters, in the first bytes.
void CheckText(const std::string& text, const std::string& name, std::string_view what) {
  const std::size_t n = std::min(text.size(), kTextCheckBytes);
  std::size_t controls = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (c == 0) {
      throw Error(
          fmt::format("'{}' is not a text file (binary data at byte {}); expected a {}",
                      name,
                      i,
                      what));
    }
    if (c < 0x20 && c != '\n' && c != '\r' && c != '\t' && c != '\f') ++controls;
  }
  if (controls * 100 > n) {
    throw Error(fmt::format(
        "'{}' is not a text file (control characters in its first bytes); expected a {}",
        name,
        what));
  }
}

std::string TooLarge(const std::string& name,
                     std::size_t max_bytes,
                     std::string_view what) {
  return fmt::format(
      "'{}' is larger than {} MiB, more than a {} holds", name, max_bytes >> 20, what);
}

}  // namespace

std::string ReadTextInput(const std::string& path,
                          std::size_t max_bytes,
                          std::string_view what) {
  const bool is_stdin = path == "-";
  const std::string name = is_stdin ? "<stdin>" : path;
  int fd = STDIN_FILENO;
  if (!is_stdin) {
    fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) {
      throw Error(
          fmt::format("cannot read {} '{}': {}", what, path, std::strerror(errno)));
    }
  }
  struct Closer {
    int fd;
    bool owns;
    ~Closer() {
      if (owns) ::close(fd);
    }
  } closer{fd, !is_stdin};
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    throw Error(fmt::format("cannot read {} '{}': {}", what, name, std::strerror(errno)));
  }
  if (S_ISDIR(st.st_mode)) {
    throw Error(fmt::format("'{}' is a directory; expected a {}", name, what));
  }
  if (!S_ISREG(st.st_mode) && !S_ISFIFO(st.st_mode)) {
    throw Error(fmt::format("'{}' is {}, not a {}; give a regular file or a pipe",
                            name,
                            FileKind(st.st_mode),
                            what));
  }
  if (S_ISREG(st.st_mode) && static_cast<std::uint64_t>(st.st_size) > max_bytes) {
    throw Error(TooLarge(name, max_bytes, what));
  }
  // Opened non-blocking so that a FIFO without a writer does not hang the
  // open; reads block again from here.
  if (!is_stdin) ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  std::string text;
  bool checked = false;
  std::size_t chunk = 65536;
  while (true) {
    const std::size_t old = text.size();
    text.resize(old + chunk);
    const ssize_t n = ::read(fd, text.data() + old, chunk);
    if (n < 0) {
      if (errno == EINTR) {
        text.resize(old);
        continue;
      }
      throw Error(
          fmt::format("error reading {} '{}': {}", what, name, std::strerror(errno)));
    }
    text.resize(old + static_cast<std::size_t>(n));
    if (n == 0) break;
    if (!checked && text.size() >= kTextCheckBytes) {
      CheckText(text, name, what);
      checked = true;
    }
    if (text.size() > max_bytes) throw Error(TooLarge(name, max_bytes, what));
    chunk = std::min<std::size_t>(chunk * 2, std::size_t{16} << 20);
  }
  if (!checked) CheckText(text, name, what);
  return text;
}

}  // namespace mpcal
