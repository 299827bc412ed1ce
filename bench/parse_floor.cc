// The speed floor of calibrate and apply: read a text log and parse every
// number in it with fast_float, nothing more (no columns, no checks, no storage). With
// --write OUT it also writes every number back with std::to_chars (the
// separators copied as they are), the floor of `mpcal apply`.
//
//   mpcal_parse_floor LOG [--write OUT]
//
// Prints the count of numbers and their sum (so that nothing is optimised
// away). bench/speed_bench.sh runs it beside mpcal and prints ratios.
#include <fcntl.h>
#include <unistd.h>

#include <charconv>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

#include <fast_float/fast_float.h>

namespace {

constexpr std::size_t kChunk = std::size_t{1} << 20;

bool StartsNumber(char c) { return (c >= '0' && c <= '9') || c == '-' || c == '.'; }

void WriteAll(int fd, const char* data, std::size_t n) {
  while (n > 0) {
    const ssize_t w = ::write(fd, data, n);
    if (w <= 0) {
      std::perror("write");
      std::exit(1);
    }
    data += w;
    n -= static_cast<std::size_t>(w);
  }
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 2 && !(argc == 4 && std::strcmp(argv[2], "--write") == 0)) {
    std::fprintf(stderr, "usage: %s LOG [--write OUT]\n", argv[0]);
    return 2;
  }
  const int fd = ::open(argv[1], O_RDONLY);
  if (fd < 0) {
    std::perror(argv[1]);
    return 1;
  }
  int out_fd = -1;
  if (argc == 4) {
    out_fd = ::open(argv[3], O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (out_fd < 0) {
      std::perror(argv[3]);
      return 1;
    }
  }
  std::vector<char> buf(kChunk);
  std::string out;
  out.reserve(2 * kChunk);
  std::size_t len = 0;
  bool eof = false;
  std::size_t count = 0;
  double sum = 0.0;
  while (!eof || len > 0) {
    if (!eof) {
      const ssize_t n = ::read(fd, buf.data() + len, buf.size() - len);
      if (n < 0) {
        std::perror("read");
        return 1;
      }
      if (n == 0) eof = true;
      len += static_cast<std::size_t>(n);
    }
    // Parse up to the last line end; the rest waits for the next read.
    std::size_t stop = len;
    if (!eof) {
      while (stop > 0 && buf[stop - 1] != '\n') --stop;
      if (stop == 0) continue;
    }
    const char* p = buf.data();
    const char* const end = buf.data() + stop;
    while (p < end) {
      const char* q = p;
      while (q < end && !StartsNumber(*q)) ++q;
      if (out_fd >= 0) out.append(p, q);
      if (q == end) {
        p = q;
        break;
      }
      double v = 0.0;
      const auto r = fast_float::from_chars(q, end, v);
      if (r.ec != std::errc()) {
        if (out_fd >= 0) out.push_back(*q);
        p = q + 1;
        continue;
      }
      sum += v;
      ++count;
      if (out_fd >= 0) {
        char number[32];
        const auto w = std::to_chars(number, number + sizeof(number), v);
        out.append(number, w.ptr);
      }
      p = r.ptr;
    }
    if (out_fd >= 0 && out.size() >= kChunk) {
      WriteAll(out_fd, out.data(), out.size());
      out.clear();
    }
    std::memmove(buf.data(), buf.data() + stop, len - stop);
    len -= stop;
    if (eof && len == 0) break;
  }
  if (out_fd >= 0) {
    WriteAll(out_fd, out.data(), out.size());
    ::close(out_fd);
  }
  ::close(fd);
  std::printf("%zu numbers, sum %.17g\n", count, sum);
  return 0;
}
