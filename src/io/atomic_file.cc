#include "mpcal/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <memory>
#include <streambuf>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "mpcal/error.h"

namespace mpcal {
namespace {

namespace fs = std::filesystem;

// An ostream buffer straight over a file descriptor: large writes, and the
// errno of a failed write kept for the message (std::ofstream loses it).
class FdStreambuf : public std::streambuf {
 public:
  // The buffer is not zeroed first: a small file (a calibration) then makes
  // resident only the pages it is written into, not the whole mebibyte.
  explicit FdStreambuf(int fd)
      : fd_(fd), buffer_(std::make_unique_for_overwrite<char[]>(kBufferBytes)) {
    setp(buffer_.get(), buffer_.get() + kBufferBytes);
  }
  ~FdStreambuf() override = default;
  FdStreambuf(const FdStreambuf&) = delete;
  FdStreambuf& operator=(const FdStreambuf&) = delete;

  /// errno of the first failed write, 0 if none.
  int error() const { return error_; }

 protected:
  int_type overflow(int_type ch) override {
    if (!Flush()) return traits_type::eof();
    if (!traits_type::eq_int_type(ch, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(ch);
      pbump(1);
    }
    return traits_type::not_eof(ch);
  }

  std::streamsize xsputn(const char* s, std::streamsize n) override {
    const std::streamsize room = epptr() - pptr();
    if (n <= room) {
      std::memcpy(pptr(), s, static_cast<std::size_t>(n));
      pbump(static_cast<int>(n));
      return n;
    }
    if (!Flush()) return 0;
    if (n >= static_cast<std::streamsize>(kBufferBytes)) {
      return WriteAll(s, static_cast<std::size_t>(n)) ? n : 0;
    }
    std::memcpy(pptr(), s, static_cast<std::size_t>(n));
    pbump(static_cast<int>(n));
    return n;
  }

  int sync() override { return Flush() ? 0 : -1; }

  // A writer that completes a header at the end (a ROS 1 bag's) seeks back;
  // on a pipe or a terminal lseek(2) fails and so does the seek.
  pos_type seekoff(off_type off,
                   std::ios_base::seekdir dir,
                   std::ios_base::openmode which) override {
    if ((which & std::ios_base::out) == 0 || !Flush()) return pos_type(off_type(-1));
    const int whence = dir == std::ios_base::beg   ? SEEK_SET
                       : dir == std::ios_base::cur ? SEEK_CUR
                                                   : SEEK_END;
    const off_t at = ::lseek(fd_, static_cast<off_t>(off), whence);
    return at < 0 ? pos_type(off_type(-1)) : pos_type(static_cast<off_type>(at));
  }
  pos_type seekpos(pos_type pos, std::ios_base::openmode which) override {
    return seekoff(off_type(pos), std::ios_base::beg, which);
  }

 private:
  bool Flush() {
    const std::size_t n = static_cast<std::size_t>(pptr() - pbase());
    setp(buffer_.get(), buffer_.get() + kBufferBytes);
    return n == 0 || WriteAll(buffer_.get(), n);
  }

  bool WriteAll(const char* data, std::size_t n) {
    if (error_ != 0) return false;
    while (n > 0) {
      const ssize_t w = ::write(fd_, data, n);
      if (w < 0) {
        if (errno == EINTR) continue;
        error_ = errno;
        return false;
      }
      data += w;
      n -= static_cast<std::size_t>(w);
    }
    return true;
  }

  static constexpr std::size_t kBufferBytes = std::size_t{1} << 20;
  int fd_;
  std::unique_ptr<char[]> buffer_;
  int error_ = 0;
};

fs::path OutputDirectory(const fs::path& target) {
  return target.has_parent_path() ? target.parent_path() : fs::path(".");
}

mode_t CurrentUmask() {
  const mode_t mask = ::umask(0);
  ::umask(mask);
  return mask;
}

// Where the bytes of an output go. A rename(2) over a device node or a FIFO
// would replace it with a regular file (as root: the system's /dev/null), and
// a rename over a symbolic link would replace the link, not the file it
// names; so only regular files (or new ones) are written through a
// temporary file, the rest directly.
struct OutputTarget {
  enum class Kind {
    kDescriptor,  // an open descriptor: "-", /dev/stdout, /dev/fd/N
    kDirect,      // a character device or FIFO, opened and written in place
    kReplace,     // a regular file or a new one: temporary file + rename
  };
  Kind kind = Kind::kReplace;
  std::string path;  // symbolic links followed
  int fd = -1;       // kDescriptor only
};

// The descriptor a path names, or -1: /dev/stdout, /dev/stderr, /dev/fd/N,
// /proc/self/fd/N. Writing through the descriptor (rather than opening the
// path anew) keeps the shell's offset and append mode of a redirection.
int DescriptorOf(const std::string& path) {
  if (path == "-" || path == "/dev/stdout") return STDOUT_FILENO;
  if (path == "/dev/stderr") return STDERR_FILENO;
  for (const std::string_view prefix : {"/dev/fd/", "/proc/self/fd/"}) {
    if (path.size() > prefix.size() && path.compare(0, prefix.size(), prefix) == 0) {
      const std::string digits = path.substr(prefix.size());
      if (digits.size() <= 6 &&
          digits.find_first_not_of("0123456789") == std::string::npos) {
        return std::stoi(digits);
      }
    }
  }
  return -1;
}

std::string DescribeDescriptor(int fd) {
  if (fd == STDOUT_FILENO) return "standard output";
  if (fd == STDERR_FILENO) return "standard error";
  return fmt::format("file descriptor {}", fd);
}

OutputTarget ResolveOutput(const std::string& path) {
  if (path.empty()) throw Error("the output file name is empty");
  std::string current = path;
  for (int hop = 0; hop < 40; ++hop) {
    if (const int fd = DescriptorOf(current); fd >= 0) {
      return {OutputTarget::Kind::kDescriptor, current, fd};
    }
    struct stat st {};
    if (::lstat(current.c_str(), &st) != 0) {
      // Not there (yet): a new file, written atomically; a missing
      // directory is CheckWritable's to explain.
      return {OutputTarget::Kind::kReplace, current, -1};
    }
    if (S_ISLNK(st.st_mode)) {
      std::string link(4096, '\0');
      const ssize_t n = ::readlink(current.c_str(), link.data(), link.size());
      if (n < 0) {
        throw Error(fmt::format("cannot write '{}': {}", path, std::strerror(errno)));
      }
      link.resize(static_cast<std::size_t>(n));
      const fs::path next(link);
      current = next.is_absolute() ? link : (OutputDirectory(current) / next).string();
      continue;
    }
    if (S_ISDIR(st.st_mode)) {
      throw Error(
          fmt::format("cannot write '{}': it is a directory; give a file name", path));
    }
    if (S_ISCHR(st.st_mode) || S_ISFIFO(st.st_mode)) {
      return {OutputTarget::Kind::kDirect, current, -1};
    }
    if (S_ISREG(st.st_mode)) {
      // Files under /proc cannot be renamed over; they are written in place.
      const bool in_proc = current.rfind("/proc/", 0) == 0;
      return {in_proc ? OutputTarget::Kind::kDirect : OutputTarget::Kind::kReplace,
              current,
              -1};
    }
    throw Error(fmt::format(
        "cannot write '{}': it is a {}, which cannot be written whole or not at all; "
        "give a "
        "regular file",
        path,
        S_ISBLK(st.st_mode) ? "block device" : "socket or other special file"));
  }
  throw Error(fmt::format("cannot write '{}': too many levels of symbolic links", path));
}

// Streams `write` into descriptor `fd`; `name` for the messages.
void WriteToDescriptor(int fd,
                       const std::string& name,
                       const std::function<void(std::ostream&)>& write) {
  FdStreambuf buf(fd);
  std::ostream out(&buf);
  write(out);
  out.flush();
  if (!out || buf.error() != 0) {
    throw Error(fmt::format("error writing to {}: {}",
                            name,
                            std::strerror(buf.error() != 0 ? buf.error() : EIO)));
  }
}

void WriteInPlace(const std::string& path,
                  const std::string& device,
                  const std::function<void(std::ostream&)>& write) {
  const int fd = ::open(device.c_str(), O_WRONLY | O_NOCTTY | O_CLOEXEC);
  if (fd < 0) {
    throw Error(fmt::format("cannot write '{}': {}", path, std::strerror(errno)));
  }
  try {
    WriteToDescriptor(fd, fmt::format("'{}'", path), write);
  } catch (...) {
    ::close(fd);
    throw;
  }
  if (::close(fd) != 0) {
    throw Error(fmt::format("error writing '{}': {}", path, std::strerror(errno)));
  }
}

// The mode of the file being replaced, so that replacing keeps it; a new file
// gets the usual permissions, as if created by open(2) (mkstemp makes 0600).
mode_t ModeFor(const std::string& target) {
  struct stat st {};
  if (::stat(target.c_str(), &st) == 0 && S_ISREG(st.st_mode)) return st.st_mode & 07777;
  return 0666 & ~CurrentUmask();
}

void ReplaceAtomically(const std::string& path,
                       const std::string& resolved,
                       const std::function<void(std::ostream&)>& write) {
  const fs::path target(resolved);
  const fs::path dir = OutputDirectory(target);
  // The temporary file sits beside the target so that rename(2) is atomic
  // (same file system), and is hidden so that a crash leaves no clutter in
  // listings.
  std::string tmp =
      (dir / fmt::format(".{}.mpcal-XXXXXX", target.filename().string())).string();
  const mode_t mode = ModeFor(resolved);
  const int fd = ::mkstemp(tmp.data());
  if (fd < 0) {
    throw Error(fmt::format("cannot write '{}': {} (is directory '{}' writable?)",
                            path,
                            std::strerror(errno),
                            dir.string()));
  }
  auto fail = [&](const std::string& message) {
    ::close(fd);
    ::unlink(tmp.c_str());
    throw Error(message);
  };
  {
    FdStreambuf buf(fd);
    std::ostream out(&buf);
    try {
      write(out);
    } catch (...) {
      ::close(fd);
      ::unlink(tmp.c_str());
      throw;
    }
    out.flush();
    if (!out || buf.error() != 0) {
      fail(fmt::format("error writing '{}': {}",
                       path,
                       std::strerror(buf.error() != 0 ? buf.error() : EIO)));
    }
  }
  if (::fchmod(fd, mode) != 0) {
    fail(fmt::format("cannot write '{}': {}", path, std::strerror(errno)));
  }
  if (::close(fd) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    throw Error(fmt::format("error writing '{}': {}", path, std::strerror(err)));
  }
  if (::rename(tmp.c_str(), resolved.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    throw Error(fmt::format("cannot write '{}': {}", path, std::strerror(err)));
  }
}

}  // namespace

void WriteFileAtomically(const std::string& path, const std::string& content) {
  WriteStreamAtomically(path, [&content](std::ostream& out) {
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
  });
}

void WriteStreamAtomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write) {
  CheckWritable(path);
  const OutputTarget target = ResolveOutput(path);
  switch (target.kind) {
    case OutputTarget::Kind::kDescriptor:
      std::fflush(stdout);
      WriteToDescriptor(target.fd, DescribeDescriptor(target.fd), write);
      return;
    case OutputTarget::Kind::kDirect:
      WriteInPlace(path, target.path, write);
      return;
    case OutputTarget::Kind::kReplace:
      ReplaceAtomically(path, target.path, write);
      return;
  }
}

void CheckWritable(const std::string& path) {
  const OutputTarget target = ResolveOutput(path);
  if (target.kind == OutputTarget::Kind::kDescriptor) {
    if (::fcntl(target.fd, F_GETFL) < 0) {
      throw Error(fmt::format(
          "cannot write '{}': {} is closed", path, DescribeDescriptor(target.fd)));
    }
    return;
  }
  if (target.kind == OutputTarget::Kind::kDirect) {
    if (::access(target.path.c_str(), W_OK) != 0) {
      throw Error(fmt::format("cannot write '{}': {}", path, std::strerror(errno)));
    }
    return;
  }
  const fs::path dir = OutputDirectory(fs::path(target.path));
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) {
    throw Error(
        fmt::format("cannot write '{}': directory '{}' does not exist; create it, or "
                    "give another path",
                    path,
                    dir.string()));
  }
  if (::access(dir.c_str(), W_OK) != 0) {
    throw Error(
        fmt::format("cannot write '{}': directory '{}' is not writable ({}); give "
                    "another path",
                    path,
                    dir.string(),
                    std::strerror(errno)));
  }
}

void RefuseOverwritingInput(const std::string& input, const std::string& output) {
  if (input == "-" || output == "-") return;
  // A device or a pipe named twice (/dev/null in and out) overwrites nothing.
  if (output.empty() || ResolveOutput(output).kind != OutputTarget::Kind::kReplace)
    return;
  std::error_code ec;
  bool same = fs::weakly_canonical(input, ec) == fs::weakly_canonical(output, ec) && !ec;
  if (!same && fs::exists(input, ec) && fs::exists(output, ec)) {
    same = fs::equivalent(input, output, ec) && !ec;
  }
  if (same) {
    throw Error(fmt::format(
        "output '{}' is the input file '{}'; mpcal does not overwrite its input: give "
        "another output path",
        output,
        input));
  }
}

void CheckOutput(const std::string& output, const std::vector<std::string>& inputs) {
  CheckWritable(output);
  for (const std::string& input : inputs) {
    if (!input.empty()) RefuseOverwritingInput(input, output);
  }
}

}  // namespace mpcal
