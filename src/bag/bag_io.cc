#include "bag/bag_io.h"

#include <filesystem>

#include "mpcal/error.h"

namespace mpcal::bag {

BagFile::BagFile(const std::string& path) : path_(path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw Error(ErrorKind::kIo, path + ": is a directory, not a bag file");
  }
  in_.open(path, std::ios::binary);
  if (!in_) throw Error(ErrorKind::kIo, path + ": cannot open the file");
  in_.seekg(0, std::ios::end);
  const auto end = in_.tellg();
  if (end < 0) throw Error(ErrorKind::kIo, path + ": cannot read the file's size");
  size_ = static_cast<std::uint64_t>(end);
}

std::string BagFile::ReadAt(std::uint64_t offset, std::uint64_t n, const char* what) {
  if (offset > size_ || n > size_ - offset) {
    throw DataError(std::string(what) + " needs " + std::to_string(n) +
                    " bytes at byte " + std::to_string(offset) + " but the file has " +
                    std::to_string(size_) + " bytes");
  }
  std::string out = ReadSome(offset, n);
  if (out.size() != n) {
    throw Error(ErrorKind::kIo, path_ + ": read error at byte " + std::to_string(offset));
  }
  return out;
}

std::string BagFile::ReadSome(std::uint64_t offset, std::uint64_t n) {
  if (offset >= size_) return {};
  if (n > size_ - offset) n = size_ - offset;
  std::string out(n, '\0');
  in_.clear();
  in_.seekg(static_cast<std::streamoff>(offset));
  in_.read(out.data(), static_cast<std::streamsize>(n));
  out.resize(static_cast<std::size_t>(in_.gcount()));
  return out;
}

void ThrowBagError(const std::string& path, const std::string& what) {
  throw Error(ErrorKind::kInput, path + ": " + what);
}

}  // namespace mpcal::bag
