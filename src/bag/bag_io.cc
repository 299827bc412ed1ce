#include "bag/bag_io.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <filesystem>
#include <new>

#include "mpcal/error.h"

namespace mpcal::bag {

BagFile::BagFile(const std::string& path) : path_(path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw Error(ErrorKind::kIo, path + ": is a directory, not a bag file");
  }
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) throw Error(ErrorKind::kIo, path + ": cannot open the file");
  struct stat st {};
  if (::fstat(fd_, &st) != 0 || st.st_size < 0) {
    ::close(fd_);
    throw Error(ErrorKind::kIo, path + ": cannot read the file's size");
  }
  size_ = static_cast<std::uint64_t>(st.st_size);
}

BagFile::~BagFile() { ::close(fd_); }

void ByteCursor::ThrowShort(std::uint64_t n, const char* what) const {
  throw DataError(std::string(what) + " needs " + std::to_string(n) +
                  " bytes at offset " + std::to_string(pos_) + " but " +
                  std::to_string(remaining()) + " remain");
}

void ByteBuffer::Free::operator()(char* p) const { std::free(p); }

void ByteBuffer::Resize(std::size_t n) {
  if (n > capacity_) {
    char* grown = static_cast<char*>(std::realloc(data_.get(), n));
    if (grown == nullptr) throw std::bad_alloc();
    static_cast<void>(data_.release());
    data_.reset(grown);
    capacity_ = n;
  }
  size_ = n;
}

namespace {

void CheckRange(std::uint64_t offset,
                std::uint64_t n,
                std::uint64_t size,
                const char* what) {
  if (offset > size || n > size - offset) {
    throw DataError(std::string(what) + " needs " + std::to_string(n) +
                    " bytes at byte " + std::to_string(offset) + " but the file has " +
                    std::to_string(size) + " bytes");
  }
}

}  // namespace

std::string BagFile::ReadAt(std::uint64_t offset, std::uint64_t n, const char* what) {
  CheckRange(offset, n, size_, what);
  std::string out = ReadSome(offset, n);
  if (out.size() != n) {
    throw Error(ErrorKind::kIo, path_ + ": read error at byte " + std::to_string(offset));
  }
  return out;
}

std::string_view BagFile::ReadInto(std::uint64_t offset,
                                   std::uint64_t n,
                                   const char* what,
                                   ByteBuffer& out) {
  CheckRange(offset, n, size_, what);
  out.Resize(static_cast<std::size_t>(n));
  if (Pread(offset, out.size(), out.data()) != n) {
    throw Error(ErrorKind::kIo, path_ + ": read error at byte " + std::to_string(offset));
  }
  return out.view();
}

std::string BagFile::ReadSome(std::uint64_t offset, std::uint64_t n) {
  if (offset >= size_) return {};
  if (n > size_ - offset) n = size_ - offset;
  std::string out(n, '\0');
  out.resize(Pread(offset, out.size(), out.data()));
  return out;
}

std::size_t BagFile::Pread(std::uint64_t offset, std::size_t n, char* out) {
  std::size_t got = 0;
  while (got < n) {
    const ssize_t rc = ::pread(fd_, out + got, n - got, static_cast<off_t>(offset + got));
    if (rc < 0 && errno == EINTR) continue;
    if (rc <= 0) break;  // an error or the end: the caller sees fewer bytes
    got += static_cast<std::size_t>(rc);
  }
  return got;
}

void ThrowBagError(const std::string& path, const std::string& what) {
  throw Error(ErrorKind::kInput, path + ": " + what);
}

}  // namespace mpcal::bag
