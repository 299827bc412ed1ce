#include "chunk_source.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <new>
#include <system_error>
#include <utility>

#include <fmt/format.h>

#include "mpcal/error.h"

namespace mpcal::logio {

#if defined(__SANITIZE_ADDRESS__)
#define MPCAL_PAGE_BUFFER_IN_HEAP 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(memory_sanitizer)
#define MPCAL_PAGE_BUFFER_IN_HEAP 1
#endif
#endif

namespace {

char* MapPages(std::size_t bytes) {
#ifdef MPCAL_PAGE_BUFFER_IN_HEAP
  return static_cast<char*>(::operator new(bytes));
#else
  void* p =
      ::mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  if (p == MAP_FAILED) throw std::bad_alloc();
  return static_cast<char*>(p);
#endif
}

void UnmapPages(char* data, std::size_t bytes) {
  if (data == nullptr) return;
#ifdef MPCAL_PAGE_BUFFER_IN_HEAP
  (void)bytes;
  ::operator delete(data);
#else
  ::munmap(data, bytes);
#endif
}

}  // namespace

PageBuffer::PageBuffer(std::size_t bytes) : data_(MapPages(bytes)), size_(bytes) {}

PageBuffer::~PageBuffer() { Release(); }

void PageBuffer::Grow(std::size_t bytes) {
  if (bytes <= size_) return;
  char* const grown = MapPages(bytes);
  if (size_ > 0) std::memcpy(grown, data_, size_);
  UnmapPages(data_, size_);
  data_ = grown;
  size_ = bytes;
}

void PageBuffer::Release() {
  UnmapPages(data_, size_);
  data_ = nullptr;
  size_ = 0;
}

void ThrowLineTooLong(const std::string& source, std::size_t line) {
  throw Error(ErrorKind::kInput,
              fmt::format("{}:{}: line longer than {} KiB: this does not look like a "
                          "text log",
                          source,
                          line,
                          kMaxLineBytes / 1024));
}

LogFile::LogFile(const std::string& path) {
  if (path == "-") {
    source_ = "<stdin>";
    fd_ = STDIN_FILENO;
    return;
  }
  source_ = path;
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    const int err = errno;
    throw Error(ErrorKind::kIo,
                fmt::format("cannot read log '{}': {}{}",
                            path,
                            std::strerror(err),
                            err == ENOENT ? " (check the path)" : ""));
  }
  if (S_ISDIR(st.st_mode)) {
    throw Error(ErrorKind::kIo,
                fmt::format("'{}' is a directory; give the path of a log file", path));
  }
  fd_ = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd_ < 0) {
    throw Error(ErrorKind::kIo,
                fmt::format("cannot read log '{}': {}", path, std::strerror(errno)));
  }
  owns_fd_ = true;
  if (S_ISREG(st.st_mode)) {
    size_ = static_cast<std::uint64_t>(st.st_size);
#ifdef POSIX_FADV_SEQUENTIAL
    ::posix_fadvise(fd_, 0, 0, POSIX_FADV_SEQUENTIAL);
#endif
  }
}

LogFile::~LogFile() {
  if (owns_fd_ && fd_ >= 0) ::close(fd_);
}

std::size_t LogFile::Read(char* dst, std::size_t n, bool fill, std::string* error) {
  std::size_t got = 0;
  while (!eof_ && got < n) {
    const ssize_t r = ::read(fd_, dst + got, n - got);
    if (r < 0) {
      if (errno == EINTR) continue;
      *error = fmt::format("error reading '{}': {}", source_, std::strerror(errno));
      break;
    }
    if (r == 0) {
      eof_ = true;
      break;
    }
    got += static_cast<std::size_t>(r);
    if (!fill) break;
  }
  return got;
}

bool LogFile::Seek(std::uint64_t offset) {
  if (!owns_fd_ || size_ == 0) return false;
  if (::lseek(fd_, static_cast<off_t>(offset), SEEK_SET) < 0) return false;
  eof_ = false;
  return true;
}

// ---------------------------------------------------------------------------

LineReader::LineReader(LogFile* file) : file_(file), buf_(kChunkBytes) { Refill(true); }

std::string_view LineReader::head() const {
  return {buf_.data() + begin_, end_ - begin_};
}

void LineReader::Skip(std::size_t n) {
  begin_ += n;
  consumed_ += n;
}

// Reads more input after the unconsumed bytes.
void LineReader::Refill(bool fill) {
  if (begin_ > 0) {
    std::memmove(buf_.data(), buf_.data() + begin_, end_ - begin_);
    end_ -= begin_;
    begin_ = 0;
  }
  if (end_ == buf_.size()) buf_.Grow(buf_.size() * 2);
  std::string error;
  const std::size_t n = file_->Read(buf_.data() + end_, buf_.size() - end_, fill, &error);
  end_ += n;
  bytes_read_ += n;
  if (!error.empty()) throw Error(ErrorKind::kIo, error);
}

bool LineReader::Next(std::string_view* text, std::string_view* eol) {
  while (true) {
    const char* start = buf_.data() + begin_;
    const auto* nl = static_cast<const char*>(std::memchr(start, '\n', end_ - begin_));
    if (nl != nullptr || (file_->eof() && begin_ < end_)) {
      const std::size_t len =
          nl != nullptr ? static_cast<std::size_t>(nl - start) : end_ - begin_;
      const char* line_end = start + len;
      const bool cr = len > 0 && line_end[-1] == '\r';
      *text = std::string_view(start, cr ? len - 1 : len);
      if (nl != nullptr) {
        *eol = std::string_view(cr ? nl - 1 : nl, cr ? 2 : 1);
      } else {
        *eol = cr ? std::string_view(line_end - 1, 1) : std::string_view();
      }
      const std::size_t taken = nl != nullptr ? len + 1 : len;
      begin_ += taken;
      consumed_ += taken;
      ++line_number_;
      return true;
    }
    if (file_->eof()) return false;
    if (end_ - begin_ >= kMaxLineBytes)
      ThrowLineTooLong(file_->source(), line_number_ + 1);
    Refill(false);
  }
}

// ---------------------------------------------------------------------------

struct ChunkPipeline::Slot {
  enum class State { kFree, kBusy, kParsed };
  State state = State::kFree;
  std::size_t sequence = 0;
  // Whole lines (the input's last line may lack its end); `size` bytes used.
  std::unique_ptr<char[]> bytes;
  std::size_t capacity = 0;
  std::size_t size = 0;
  ChunkRows rows;
  std::exception_ptr error;  // from reading or parsing (out of memory)

  // Room for `n` bytes, keeping the first `keep`.
  void Reserve(std::size_t n, std::size_t keep) {
    if (capacity >= n) return;
    auto grown = std::make_unique_for_overwrite<char[]>(n);
    if (keep > 0) std::memcpy(grown.get(), bytes.get(), keep);
    bytes = std::move(grown);
    capacity = n;
  }
};

ChunkPipeline::ChunkPipeline(LogFile* file,
                             std::string_view first_bytes,
                             RowConversion conversion)
    : file_(file), conversion_(conversion), head_(first_bytes) {
  for (auto& slot : slots_) slot = std::make_unique<Slot>();
  try {
    helper_ = std::thread([this] {
      while (Slot* c = Claim(/*wait=*/true)) Parse(c);
    });
  } catch (const std::system_error&) {
    // No second thread: the calling thread does it all.
  }
}

ChunkPipeline::~ChunkPipeline() { Stop(); }

void ChunkPipeline::Stop() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  ready_.notify_all();
  if (helper_.joinable()) helper_.join();
}

bool ChunkPipeline::NextReady() const {
  const Slot& next = *slots_[merged_ % kChunksInFlight];
  return next.state == Slot::State::kParsed && next.sequence == merged_;
}

const ChunkRows* ChunkPipeline::Next() {
  while (true) {
    {
      std::unique_lock lock(mutex_);
      if (NextReady()) {
        Slot& next = *slots_[merged_ % kChunksInFlight];
        if (next.error) std::rethrow_exception(next.error);
        return &next.rows;
      }
      if (input_done_ && merged_ == claimed_) return nullptr;
    }
    if (Slot* c = Claim(/*wait=*/false)) {
      Parse(c);
      continue;
    }
    std::unique_lock lock(mutex_);
    ready_.wait(lock, [&] {
      return NextReady() || (input_done_ && merged_ == claimed_) ||
             (!helper_.joinable() && !input_done_);
    });
  }
}

void ChunkPipeline::Release() {
  {
    std::lock_guard lock(mutex_);
    Slot& c = *slots_[merged_ % kChunksInFlight];
    consumed_ += c.size;
    c.state = Slot::State::kFree;
    ++merged_;
  }
  ready_.notify_all();
}

// Claims the next chunk in file order and reads it; nullptr when the input
// has ended, or when there is no free slot and `wait` is false.
ChunkPipeline::Slot* ChunkPipeline::Claim(bool wait) {
  std::unique_lock read_lock(read_mutex_, std::defer_lock);
  if (wait) {
    read_lock.lock();
  } else if (!read_lock.try_lock()) {
    return nullptr;
  }
  Slot* c = nullptr;
  {
    std::unique_lock lock(mutex_);
    auto free = [&] {
      return slots_[claimed_ % kChunksInFlight]->state == Slot::State::kFree;
    };
    if (wait) ready_.wait(lock, [&] { return stop_ || input_done_ || free(); });
    if (stop_ || input_done_ || !free()) return nullptr;
    c = slots_[claimed_ % kChunksInFlight].get();
    c->state = Slot::State::kBusy;
    c->sequence = claimed_;
  }
  bool got = true;
  c->error = nullptr;
  try {
    got = Read(c);
  } catch (...) {  // out of memory: reported when this chunk's turn comes
    c->error = std::current_exception();
    c->size = 0;
  }
  std::lock_guard lock(mutex_);
  if (!got) {
    c->state = Slot::State::kFree;
    input_done_ = true;
    ready_.notify_all();
    return nullptr;
  }
  ++claimed_;
  if (!c->rows.read_error.empty() || c->rows.line_too_long || c->error)
    input_done_ = true;
  return c;
}

// The header is found in the first chunk only: that chunk reaches past it.
std::size_t ChunkPipeline::FirstChunkBytes(const Slot* c) const {
  return c->sequence == 0 ? conversion_.header_end : 0;
}

// Fills `c` with the next whole lines of the head, about kParseChunkBytes,
// copied a chunk at a time: the head is a mebibyte, and a copy of it whole
// would be held while the whole log is read. False when what is left of the
// head is to begin a chunk read from the file (it is then the carry).
bool ChunkPipeline::TakeFromHead(Slot* c) {
  if (head_.empty()) return false;
  std::size_t take = head_.size();
  const std::size_t limit = std::max(kParseChunkBytes, FirstChunkBytes(c));
  if (take > limit) {
    const auto* nl = static_cast<const char*>(::memrchr(head_.data(), '\n', limit));
    if (nl != nullptr) take = static_cast<std::size_t>(nl - head_.data()) + 1;
  }
  if (take == head_.size() && !file_->eof()) {
    carry_.assign(head_.begin(), head_.end());
    head_ = {};
    return false;
  }
  c->Reserve(take, 0);
  std::memcpy(c->bytes.get(), head_.data(), take);
  c->size = take;
  head_.remove_prefix(take);
  return true;
}

// Fills `c` with the carried-over bytes and whole lines read after them,
// about kParseChunkBytes; false when the input has ended.
bool ChunkPipeline::Read(Slot* c) {
  ChunkRows& rows = c->rows;
  rows.read_error.clear();
  rows.line_too_long = false;
  if (TakeFromHead(c)) return true;
  std::size_t size = carry_.size();
  std::size_t want = std::max({kParseChunkBytes, size, FirstChunkBytes(c)});
  c->Reserve(want, 0);
  // An empty carry has no buffer: memcpy's null source is undefined even
  // for zero bytes.
  if (size > 0) std::memcpy(c->bytes.get(), carry_.data(), size);
  carry_.clear();
  while (true) {
    size += file_->Read(c->bytes.get() + size, want - size, true, &rows.read_error);
    if (size == 0 && rows.read_error.empty()) return false;
    if (file_->eof() && rows.read_error.empty()) break;  // the rest of the input
    // Cut after the last line end; the rest begins the next chunk. (A read
    // error comes after the whole lines before it.)
    const char* const data = c->bytes.get();
    const auto* nl = static_cast<const char*>(::memrchr(data, '\n', size));
    if (nl != nullptr) {
      const std::size_t cut = static_cast<std::size_t>(nl - data) + 1;
      if (rows.read_error.empty()) carry_.assign(data + cut, data + size);
      size = cut;
      break;
    }
    if (!rows.read_error.empty()) {
      size = 0;
      break;
    }
    // One line so far, from the chunk's start (the carry starts a line).
    if (size >= kMaxLineBytes) {
      rows.line_too_long = true;
      size = 0;
      break;
    }
    want = size + kParseChunkBytes;
    c->Reserve(want, size);
  }
  c->size = size;
  return true;
}

void ChunkPipeline::Parse(Slot* c) {
  try {
    if (!c->error) ParseLines(c);
  } catch (...) {
    c->error = std::current_exception();
  }
  {
    std::lock_guard lock(mutex_);
    c->state = Slot::State::kParsed;
  }
  ready_.notify_all();
}

namespace {

enum class LineVerdict { kRow, kSkip, kStop };

// The line at `*p` the careful way (what the fast path declines): its end
// found first, then the header, comments, blank lines, the first malformed
// line and what follows it. Moves `*p` to the next line.
LineVerdict ParseLineSlowly(const RowConversion& conv,
                            std::size_t line,
                            const char* end,
                            const char** p,
                            ChunkRows* out,
                            LogLine* row) {
  const auto* nl = static_cast<const char*>(std::memchr(*p, '\n', end - *p));
  const char* const stop = nl != nullptr ? nl : end;
  std::string_view text(*p, static_cast<std::size_t>(stop - *p));
  if (!text.empty() && text.back() == '\r') text.remove_suffix(1);
  *p = nl != nullptr ? nl + 1 : end;
  if (out->failure_line > 0) {
    if (Trim(text).empty()) return LineVerdict::kSkip;
    out->failure_fatal = true;
    return LineVerdict::kStop;
  }
  if (!out->has_content) out->has_content = !Trim(text).empty();
  if (line == out->header_line || IsCommentOrBlank(text)) return LineVerdict::kSkip;
  RowFailure why;
  if (!conv.parser->Parse(text, row, &why)) {
    out->failure_line = line;
    out->failure = conv.parser->Problem(text, why);
    return LineVerdict::kSkip;
  }
  return LineVerdict::kRow;
}

}  // namespace

void ParseChunkLines(const RowConversion& conv,
                     std::string_view bytes,
                     std::size_t header_line,
                     ChunkRows* rows) {
  ChunkRows& out = *rows;
  out.bytes = bytes;
  out.header_line = header_line;
  out.time.clear();
  out.accel.clear();
  out.gyro.clear();
  out.last_row_line = 0;
  out.first_row_bytes = 0;
  out.has_content = false;
  out.failure_line = 0;
  out.failure.clear();
  out.failure_fatal = false;
  const char* p = bytes.data();
  const char* const end = p + bytes.size();
  std::size_t line = 0;
  LogLine row;
  std::array<double, kGz + 1> by_role{};
  while (p < end) {
    const char* const line_begin = p;
    ++line;
    // The fast path: a plain data row, parsed as its end is found.
    const char* next = out.failure_line == 0 && line != out.header_line
                           ? conv.parser->ParseInChunk(p, end, by_role.data())
                           : nullptr;
    if (next != nullptr) {
      p = next;
      out.has_content = true;
      row.time_raw = by_role[kTime];
      row.accel = {by_role[kAx], by_role[kAy], by_role[kAz]};
      row.gyro = {by_role[kGx], by_role[kGy], by_role[kGz]};
    } else {
      const LineVerdict verdict = ParseLineSlowly(conv, line, end, &p, &out, &row);
      if (verdict == LineVerdict::kStop) break;
      if (verdict == LineVerdict::kSkip) continue;
    }
    if (out.time.empty()) out.first_row_bytes = static_cast<std::size_t>(p - line_begin);
    out.time.push_back(conv.index_time ? static_cast<double>(out.time.size())
                                       : row.time_raw * conv.time_scale);
    out.accel.push_back(row.accel);
    if (conv.gyro) out.gyro.push_back(row.gyro * conv.gyro_scale);
    out.last_row_line = line;
  }
  // Lines after a fatal failure are not needed (the sink stops there).
  out.lines = line;
}

void ChunkPipeline::ParseLines(Slot* c) const {
  ParseChunkLines(conversion_,
                  std::string_view(c->bytes.get(), c->size),
                  c->sequence == 0 ? conversion_.header_line : 0,
                  &c->rows);
}

}  // namespace mpcal::logio
