#include "mpcal/atomic_file.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <streambuf>
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
  explicit FdStreambuf(int fd) : fd_(fd), buffer_(std::size_t{1} << 20) {
    setp(buffer_.data(), buffer_.data() + buffer_.size());
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
    if (n >= static_cast<std::streamsize>(buffer_.size())) {
      return WriteAll(s, static_cast<std::size_t>(n)) ? n : 0;
    }
    std::memcpy(pptr(), s, static_cast<std::size_t>(n));
    pbump(static_cast<int>(n));
    return n;
  }

  int sync() override { return Flush() ? 0 : -1; }

 private:
  bool Flush() {
    const std::size_t n = static_cast<std::size_t>(pptr() - pbase());
    setp(buffer_.data(), buffer_.data() + buffer_.size());
    return n == 0 || WriteAll(buffer_.data(), n);
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

  int fd_;
  std::vector<char> buffer_;
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

}  // namespace

void WriteFileAtomically(const std::string& path, const std::string& content) {
  WriteStreamAtomically(path, [&content](std::ostream& out) {
    out.write(content.data(), static_cast<std::streamsize>(content.size()));
  });
}

void WriteStreamAtomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write) {
  if (path == "-") {
    std::fflush(stdout);
    FdStreambuf buf(STDOUT_FILENO);
    std::ostream out(&buf);
    write(out);
    out.flush();
    if (!out || buf.error() != 0) {
      throw Error(fmt::format("error writing to standard output: {}",
                              std::strerror(buf.error() != 0 ? buf.error() : EIO)));
    }
    return;
  }
  CheckWritable(path);
  const fs::path target(path);
  const fs::path dir = OutputDirectory(target);
  // The temporary file sits beside the target so that rename(2) is atomic
  // (same file system), and is hidden so that a crash leaves no clutter in
  // listings.
  std::string tmp =
      (dir / fmt::format(".{}.mpcal-XXXXXX", target.filename().string())).string();
  const int fd = ::mkstemp(tmp.data());
  if (fd < 0) {
    throw Error(fmt::format("cannot write '{}': {} (is directory '{}' writable?)", path,
                            std::strerror(errno), dir.string()));
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
      fail(fmt::format("error writing '{}': {}", path,
                       std::strerror(buf.error() != 0 ? buf.error() : EIO)));
    }
  }
  // mkstemp makes the file private (0600); an output file gets the usual
  // permissions, as if created by open(2).
  if (::fchmod(fd, 0666 & ~CurrentUmask()) != 0) {
    fail(fmt::format("cannot write '{}': {}", path, std::strerror(errno)));
  }
  if (::close(fd) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    throw Error(fmt::format("error writing '{}': {}", path, std::strerror(err)));
  }
  if (::rename(tmp.c_str(), path.c_str()) != 0) {
    const int err = errno;
    ::unlink(tmp.c_str());
    throw Error(fmt::format("cannot write '{}': {}", path, std::strerror(err)));
  }
}

void CheckWritable(const std::string& path) {
  if (path == "-") return;
  if (path.empty()) throw Error("no output file given");
  const fs::path target(path);
  std::error_code ec;
  if (fs::is_directory(target, ec)) {
    throw Error(fmt::format("cannot write '{}': it is a directory; give a file name", path));
  }
  const fs::path dir = OutputDirectory(target);
  if (!fs::is_directory(dir, ec)) {
    throw Error(fmt::format(
        "cannot write '{}': directory '{}' does not exist; create it, or give another path",
        path, dir.string()));
  }
  if (::access(dir.c_str(), W_OK) != 0) {
    throw Error(fmt::format("cannot write '{}': directory '{}' is not writable ({}); give "
                            "another path",
                            path, dir.string(), std::strerror(errno)));
  }
}

void RefuseOverwritingInput(const std::string& input, const std::string& output) {
  if (input == "-" || output == "-") return;
  std::error_code ec;
  bool same = fs::weakly_canonical(input, ec) == fs::weakly_canonical(output, ec) && !ec;
  if (!same && fs::exists(input, ec) && fs::exists(output, ec)) {
    same = fs::equivalent(input, output, ec) && !ec;
  }
  if (same) {
    throw Error(fmt::format(
        "output '{}' is the input file '{}'; mpcal does not overwrite its input: give "
        "another output path",
        output, input));
  }
}

void CheckOutput(const std::string& output, const std::vector<std::string>& inputs) {
  CheckWritable(output);
  for (const std::string& input : inputs) {
    if (!input.empty()) RefuseOverwritingInput(input, output);
  }
}

}  // namespace mpcal
