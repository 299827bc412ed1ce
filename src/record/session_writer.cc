// The session file, written as the lines arrive. Not an atomic write (the
// point is that the file holds what came, whatever stops the session), so
// the path is checked as every output's is, by hand: never a device, a FIFO,
// a socket, a directory or a symbolic link, never the input. The file is
// created at the first text, so that a session that received nothing leaves
// no file and replaces none.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

#include <fmt/format.h>

#include "mpcal/atomic_file.h"
#include "mpcal/error.h"
#include "mpcal/live_source.h"

namespace mpcal {
namespace {

// Text held before it is written: a few hundred lines at most, so that a
// crash between two Flush calls loses little.
constexpr std::size_t kBufferBytes = 4096;

[[noreturn]] void Refuse(const std::string& path, const std::string& why) {
  throw Error(ErrorKind::kIo, fmt::format("session file '{}': {}", path, why));
}

// What may not be replaced by a session file, or "" when `path` may be.
std::string Obstacle(const std::string& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return "";
  if (S_ISLNK(st.st_mode)) {
    return "is a symbolic link; give the path of a file (the link is never replaced "
           "or written through)";
  }
  if (S_ISDIR(st.st_mode)) return "is a directory; give a file name in it";
  if (!S_ISREG(st.st_mode)) {
    return "is a device, a FIFO or a socket, not a file; give the path of a file";
  }
  return "";
}

void CheckDirectory(const std::string& path) {
  std::filesystem::path dir = std::filesystem::path(path).parent_path();
  if (dir.empty()) dir = ".";
  struct stat st {};
  if (::stat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) {
    Refuse(
        path,
        fmt::format("the directory '{}' does not exist; create it first", dir.string()));
  }
  if (::access(dir.c_str(), W_OK) != 0) {
    Refuse(path,
           fmt::format("the directory '{}' is not writable ({}); give a path in "
                       "a directory you can write",
                       dir.string(),
                       std::strerror(errno)));
  }
}

}  // namespace

SessionWriter::SessionWriter(const std::string& path, const std::string& input_spec)
    : path_(path) {
  if (path.empty()) throw Error(ErrorKind::kOption, "session file: the path is empty");
  if (path == "-") {
    Refuse(path, "the session is written to a file, as it arrives; give its path");
  }
  const std::string obstacle = Obstacle(path);
  if (!obstacle.empty()) Refuse(path, obstacle);
  CheckDirectory(path);
  if (!input_spec.empty() && input_spec != "-") RefuseOverwritingInput(input_spec, path);
}

SessionWriter::~SessionWriter() {
  try {
    Close();
  } catch (...) {  // the destructor keeps what was written; Close reports errors
  }
}

void SessionWriter::WriteAll(const char* data, std::size_t size) {
  if (fd_ < 0) {
    const std::string obstacle = Obstacle(path_);  // again: it may have appeared since
    if (!obstacle.empty()) Refuse(path_, obstacle);
    fd_ = ::open(
        path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_CLOEXEC, 0666);
    if (fd_ < 0) {
      Refuse(path_, fmt::format("cannot be created ({})", std::strerror(errno)));
    }
  }
  while (size > 0) {
    const ssize_t n = ::write(fd_, data, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      Refuse(path_,
             fmt::format("writing failed ({}); the file holds the session up "
                         "to {} bytes",
                         std::strerror(errno),
                         written_));
    }
    data += n;
    size -= static_cast<std::size_t>(n);
    written_ += static_cast<std::size_t>(n);
  }
}

void SessionWriter::Write(std::string_view text) {
  if (closed_) Refuse(path_, "written after it was closed");
  buffer_.append(text);
  if (buffer_.size() >= kBufferBytes) Flush();
}

void SessionWriter::Flush() {
  if (buffer_.empty()) return;
  const std::string text = std::move(buffer_);
  buffer_.clear();
  WriteAll(text.data(), text.size());
}

bool SessionWriter::Close() {
  if (closed_) return fd_kept_;
  closed_ = true;
  try {
    Flush();
  } catch (...) {
    if (fd_ >= 0) ::close(fd_);
    fd_kept_ = fd_ >= 0;
    fd_ = -1;
    throw;
  }
  fd_kept_ = fd_ >= 0;
  if (fd_ >= 0 && ::close(fd_) != 0) {
    fd_ = -1;
    Refuse(path_, fmt::format("closing failed ({})", std::strerror(errno)));
  }
  fd_ = -1;
  return fd_kept_;
}

}  // namespace mpcal
