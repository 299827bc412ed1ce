// Private to src/bag/: the bounded reads every container reader is built on.
// A length read from a file is checked against what remains (of the file or
// of the buffer) before anything is read or allocated, so a damaged length
// makes a DataError, never a read past the end or an unbounded allocation.
#pragma once

#include <cstdint>
#include <cstring>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>

namespace mpcal::bag {

/// Malformed content found below the record level; the container reader
/// turns it into an mpcal::Error naming the file and the record.
class DataError : public std::runtime_error {
 public:
  explicit DataError(const std::string& what) : std::runtime_error(what) {}
};

/// Little-endian reads from a buffer; every read checks what remains.
class ByteCursor {
 public:
  explicit ByteCursor(std::string_view data) : data_(data) {}
  // The cursor views its bytes: a temporary string would leave it dangling.
  explicit ByteCursor(std::string&&) = delete;

  std::size_t offset() const { return pos_; }
  std::size_t remaining() const { return data_.size() - pos_; }
  bool empty() const { return pos_ == data_.size(); }

  std::string_view Bytes(std::uint64_t n, const char* what) {
    // Called for every field of every message: the check stays inline, the
    // message it throws is built out of line.
    if (n > remaining()) [[unlikely]]
      ThrowShort(n, what);
    const std::string_view out(data_.data() + pos_, n);
    pos_ += n;
    return out;
  }
  void Skip(std::uint64_t n, const char* what) { Bytes(n, what); }
  /// Moves to the next multiple of `alignment` counted from `origin`.
  void Align(std::size_t alignment, std::size_t origin, const char* what) {
    const std::size_t misalign = (pos_ - origin) % alignment;
    if (misalign != 0) Skip(alignment - misalign, what);
  }

  template <typename T>
  T Read(const char* what, bool big_endian = false) {
    const std::string_view b = Bytes(sizeof(T), what);
    T value;
    if (!big_endian) {
      std::memcpy(&value, b.data(), sizeof(T));
      return value;
    }
    unsigned char raw[sizeof(T)];
    for (std::size_t i = 0; i < sizeof(T); ++i) raw[i] = b[sizeof(T) - 1 - i];
    std::memcpy(&value, raw, sizeof(T));
    return value;
  }
  std::uint8_t U8(const char* what) { return Read<std::uint8_t>(what); }
  std::uint16_t U16(const char* what) { return Read<std::uint16_t>(what); }
  std::uint32_t U32(const char* what) { return Read<std::uint32_t>(what); }
  std::uint64_t U64(const char* what) { return Read<std::uint64_t>(what); }

 private:
  [[noreturn]] void ThrowShort(std::uint64_t n, const char* what) const;

  std::string_view data_;
  std::size_t pos_ = 0;
};

/// Bytes that are always written before they are read (a chunk as read, as
/// unpacked): allocated without the zero-fill a std::string or std::vector
/// makes first, which for megabyte chunks costs as much as the copy itself.
class ByteBuffer {
 public:
  char* data() { return data_.get(); }
  std::size_t size() const { return size_; }
  std::string_view view() const { return {data_.get(), size_}; }
  /// Makes the size `n`, keeping the first min(size, n) bytes; the others
  /// hold whatever the allocator left there until written.
  void Resize(std::size_t n);

 private:
  struct Free {
    void operator()(char* p) const;
  };
  std::unique_ptr<char, Free> data_;
  std::size_t size_ = 0;
  std::size_t capacity_ = 0;
};

/// A file read at offsets, never held whole. Each read is one pread(2) into
/// its result: the readers jump between records, and a stream's buffer would
/// be refilled (and its bytes copied once more) after every seek.
class BagFile {
 public:
  /// \throws mpcal::Error when the file cannot be opened.
  explicit BagFile(const std::string& path);
  ~BagFile();
  BagFile(const BagFile&) = delete;
  BagFile& operator=(const BagFile&) = delete;

  const std::string& path() const { return path_; }
  std::uint64_t size() const { return size_; }
  /// Reads `n` bytes at `offset`.
  /// \throws DataError when they run past the end of the file.
  std::string ReadAt(std::uint64_t offset, std::uint64_t n, const char* what);
  /// Like ReadAt, into `out` (a chunk: no zero-fill first); views `out`.
  std::string_view ReadInto(std::uint64_t offset,
                            std::uint64_t n,
                            const char* what,
                            ByteBuffer& out);
  /// Like ReadAt but returns what there is (fewer bytes at the end).
  std::string ReadSome(std::uint64_t offset, std::uint64_t n);

 private:
  /// Reads up to `n` bytes at `offset` into `out`; returns how many.
  std::size_t Pread(std::uint64_t offset, std::size_t n, char* out);

  std::string path_;
  int fd_ = -1;
  std::uint64_t size_ = 0;
};

/// "path: what" as an mpcal::Error of kind kInput.
[[noreturn]] void ThrowBagError(const std::string& path, const std::string& what);

}  // namespace mpcal::bag
