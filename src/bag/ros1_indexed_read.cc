#include "bag/ros1_indexed_read.h"

#include <algorithm>
#include <cstring>
#include <optional>
#include <string>
#include <vector>

#include "mpcal/bag.h"

namespace mpcal::bag::ros1 {
namespace {

// Records whose starts are closer than this are read by one pread: the
// bytes between cost less to copy than a system call, and the page cache
// holds them whole anyway.
constexpr std::uint64_t kJoinGap = 4096;
// Bytes read from a span's last record on: a sensor_msgs/Imu record is
// about 380 bytes; a longer record is read again on its own.
constexpr std::uint64_t kRecordGuess = 512;
constexpr std::uint64_t kEntryBytes = 12;  // time (u32 sec, u32 nsec), offset (u32)
// The least a sensor_msgs/Imu message record takes: its header (the
// length, op, conn and time fields: 4 + 8 + 13 + 17) and data length (4),
// then seq, stamp and the frame's length (16) and 37 doubles (296).
constexpr std::uint64_t kLeastImuRecordBytes = 4 + 38 + 4 + 16 + 296;

struct Entry {
  std::uint64_t offset = 0;  // in the chunk's data
  std::int64_t time_ns = 0;
  std::uint32_t conn = 0;
};

// The entries of `ids` in the index data records that follow a chunk (the
// first other record ends them), in the chunk's order; nullopt, read no
// further, when they are more than the `expected` the chunk info counts.
std::optional<std::vector<Entry>> EntriesAfter(BagFile& file,
                                               std::uint64_t pos,
                                               const std::set<std::uint32_t>& ids,
                                               std::uint64_t expected) {
  std::vector<Entry> entries;
  while (pos < file.size()) {
    const Record r = RecordAt(file, pos);
    if (r.op != kIndexData) break;
    const std::uint32_t conn = U32Field(r.fields, "conn");
    if (ids.count(conn) != 0) {
      if (U32Field(r.fields, "ver") != 1)
        throw DataError("an index data record of a version other than 1");
      const std::uint64_t count = U32Field(r.fields, "count");
      if (entries.size() + count > expected) return std::nullopt;
      if (count * kEntryBytes != r.data_length || r.data_length > kBagMaxRecordBytes) {
        throw DataError("an index data record of " + std::to_string(count) +
                        " entries holds " + std::to_string(r.data_length) + " bytes");
      }
      const std::string data = file.ReadAt(r.data_offset, r.data_length, "index data");
      for (const IndexDataEntry& e :
           ParseIndexData(data, static_cast<std::uint32_t>(count))) {
        entries.push_back({e.offset, e.time_ns, conn});
      }
    }
    pos = r.next;
  }
  std::stable_sort(entries.begin(), entries.end(), [](const Entry& a, const Entry& b) {
    return a.offset < b.offset;
  });
  return entries;
}

// Entries [first, last) read by one pread of the chunk's bytes [begin, end).
struct Span {
  std::size_t first = 0, last = 0;
  std::uint64_t begin = 0, end = 0;
};

std::vector<Span> SpansOf(const std::vector<Entry>& entries, std::uint64_t chunk_bytes) {
  std::vector<Span> spans;
  for (std::size_t k = 0; k < entries.size(); ++k) {
    const std::uint64_t at = entries[k].offset;
    if (at >= chunk_bytes) {
      throw DataError("the index gives a message at offset " + std::to_string(at) +
                      " of a chunk of " + std::to_string(chunk_bytes) + " bytes");
    }
    if (k > 0 && at == entries[k - 1].offset) {
      throw DataError("the index gives two messages at offset " + std::to_string(at));
    }
    if (spans.empty() || at - entries[k - 1].offset > kRecordGuess + kJoinGap) {
      spans.push_back({k, k, at, at});
    }
    spans.back().last = k + 1;
    spans.back().end = std::min(at + kRecordGuess, chunk_bytes);
  }
  return spans;
}

// Whether the record starting at `at` lies whole in `bytes`.
bool Holds(std::string_view bytes, std::uint64_t at) {
  std::uint32_t length = 0;
  if (bytes.size() - at < sizeof length) return false;
  std::memcpy(&length, bytes.data() + at, sizeof length);
  const std::uint64_t data_at = at + sizeof length + length;
  if (data_at + sizeof length > bytes.size()) return false;
  std::memcpy(&length, bytes.data() + data_at, sizeof length);
  return data_at + sizeof length + length <= bytes.size();
}

void CheckMatches(const Record& r, const Entry& e) {
  if (r.op == kMessageData && r.conn == e.conn && r.time_ns == e.time_ns) {
    return;
  }
  throw DataError("the index gives a message of connection " + std::to_string(e.conn) +
                  " at offset " + std::to_string(e.offset) +
                  " of the chunk, and the record there is not it");
}

}  // namespace

bool ReadIndexedMessages(BagFile& file,
                         const Record& chunk,
                         const std::set<std::uint32_t>& ids,
                         std::uint64_t expected,
                         const MessageRecordHandler& on_message,
                         ByteBuffer& buffer) {
  // Whether the records could fill half the chunk is known before its
  // index is read: in an IMU-only recording they fill all of it.
  if (2 * expected * kLeastImuRecordBytes > chunk.data_length ||
      U32Field(chunk.fields, "size") != chunk.data_length) {
    return false;
  }
  const std::optional<std::vector<Entry>> found =
      EntriesAfter(file, chunk.next, ids, expected);
  if (!found || found->size() != expected) return false;
  const std::vector<Entry>& entries = *found;
  const std::vector<Span> spans = SpansOf(entries, chunk.data_length);
  std::uint64_t planned = 0;
  for (const Span& s : spans) planned += s.end - s.begin;
  if (2 * planned > chunk.data_length) return false;

  for (const Span& s : spans) {
    const std::string_view bytes = file.ReadInto(chunk.data_offset + s.begin,
                                                 s.end - s.begin,
                                                 "the chunk's indexed records",
                                                 buffer);
    for (std::size_t k = s.first; k < s.last; ++k) {
      const Entry& e = entries[k];
      const std::uint64_t at = e.offset - s.begin;
      if (s.end < chunk.data_length && !Holds(bytes, at)) {
        // Longer than the guess: read on its own, within the chunk.
        const Record r = RecordAt(file, chunk.data_offset + e.offset);
        if (r.next > chunk.data_offset + chunk.data_length)
          throw DataError("a record runs past the end of its chunk");
        if (r.data_length > kBagMaxRecordBytes)
          throw DataError("a record above the size cap");
        CheckMatches(r, e);
        on_message(r, file.ReadAt(r.data_offset, r.data_length, "the record data"));
        continue;
      }
      const Record r = RecordIn(bytes, at);
      CheckMatches(r, e);
      on_message(r, bytes.substr(r.data_offset, r.data_length));
    }
  }
  return true;
}

}  // namespace mpcal::bag::ros1
