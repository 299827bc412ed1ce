// What the file-reading fuzz targets share: the input written to an in-memory
// file (memfd) whose /proc path the reader opens, so that it runs exactly as
// on a file from disk (stat, the regular-file size, read(2) at offsets)
// without touching the disk; and the check that turns a broken invariant
// into a finding.
#pragma once

#include <sys/mman.h>
#include <unistd.h>

#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <string>

namespace mpcal::fuzz {

/// Writes `size` bytes at `data` into this process's one in-memory file
/// (made on the first call) and returns the path that opens it.
inline std::string WriteMemoryFile(const void* data, std::size_t size) {
  static const int fd = [] {
    const int f = ::memfd_create("mpcal_fuzz_input", MFD_CLOEXEC);
    if (f < 0) {
      std::perror("memfd_create");
      std::abort();
    }
    return f;
  }();
  if (::ftruncate(fd, 0) != 0 ||
      ::pwrite(fd, data, size, 0) != static_cast<ssize_t>(size)) {
    std::perror("memfd write");
    std::abort();
  }
  return "/proc/self/fd/" + std::to_string(fd);
}

/// A finding: the reader returned without an error but broke `what`.
inline void Check(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "invariant broken: %s\n", what);
    std::abort();
  }
}

}  // namespace mpcal::fuzz
