// Private to src/bag/: the records of a ROS 1 bag, format 2.0.
//
// Layout from the format's reference reader, rosbag/bag.py in Debian's
// python3-rosbag 1.15.15+ds-2 (/usr/lib/python3/dist-packages/rosbag/bag.py):
// op codes at lines 1771-1777; a record header as length-prefixed
// "name=value" fields at 2013-2052; the bag header record at 2705-2721;
// connection records at 2723-2737; chunk info records at 2739-2764; the chunk
// header (compression, size) at 2766-2776 and as written at 1721-1728; index
// data records at 2778. Also wiki.ros.org/Bags/Format/2.0.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "bag/bag_io.h"

namespace mpcal::bag::ros1 {

inline constexpr std::string_view kMagic = "#ROSBAG V2.0\n";

enum Op : std::uint8_t {
  kMessageData = 0x02,
  kBagHeader = 0x03,
  kIndexData = 0x04,
  kChunk = 0x05,
  kChunkInfo = 0x06,
  kConnection = 0x07,
};

/// A record's header fields (u32 length + "name=value" each), checked once
/// and then looked up in place: a header holds three to six fields, and a
/// message record's header is read for every message, so building a map of
/// strings for each would cost more than the message's decoding. The pass
/// that checks the fields also notes where the three a message record is
/// read by (op, conn, time) are, so looking them up scans nothing again;
/// any other name is found by a scan.
class Fields {
 public:
  Fields() = default;
  /// Fields over `header`, which must outlive them (a chunk's contents).
  /// \throws DataError for a field without '=' or running past the header.
  static Fields Viewing(std::string_view header);
  /// Fields over their own copy of `header`.
  static Fields Owning(std::string header);

  /// The value of the field `name`; of the last one when a name repeats, as
  /// rosbag's reader keeps the last (bag.py 2013-2052, a dict).
  std::optional<std::string_view> Find(std::string_view name) const;
  std::size_t count(std::string_view name) const { return Find(name) ? 1 : 0; }
  /// The op, conn and time fields as the check noted them (nullopt when
  /// absent): Find without the name's comparisons.
  std::optional<std::string_view> Op() const { return Value(op_); }
  std::optional<std::string_view> Conn() const { return Value(conn_); }
  std::optional<std::string_view> Time() const { return Value(time_); }

 private:
  // Where a noted field's value is in bytes(); an offset, not a view, so
  // that it survives the copy of owned bytes.
  struct Noted {
    std::size_t pos = 0;
    std::size_t size = 0;
    bool found = false;
  };
  std::string_view bytes() const { return owning_ ? std::string_view(owned_) : view_; }
  /// Checks every field and notes op, conn and time.
  void Check();
  const Noted* NotedFor(std::string_view name) const;
  std::optional<std::string_view> Value(const Noted& noted) const {
    if (!noted.found) return std::nullopt;
    return bytes().substr(noted.pos, noted.size);
  }

  std::string owned_;
  std::string_view view_;
  bool owning_ = false;
  Noted op_, conn_, time_;
};

/// Parses the header fields of one record into fields that own their bytes.
/// \throws DataError for a field without '=' or running past the header.
Fields ParseFields(std::string_view header);

/// The op field of a record.
/// \throws DataError when it is missing or not one byte.
std::uint8_t OpOf(const Fields& fields);
std::uint32_t U32Field(const Fields& fields, std::string_view name);
std::uint64_t U64Field(const Fields& fields, std::string_view name);
/// A ROS time field (u32 sec, u32 nsec) in ns.
std::int64_t TimeField(const Fields& fields, std::string_view name);
std::string StringField(const Fields& fields, std::string_view name);

/// A record read from a buffer (a chunk's contents) or from the file.
struct Record {
  Fields fields;
  std::uint8_t op = 0;
  /// Where the data starts (in the buffer or the file) and its length.
  std::uint64_t data_offset = 0;
  std::uint32_t data_length = 0;
  /// Where the next record starts.
  std::uint64_t next = 0;
  /// A message data record's connection and time (ns), read with its
  /// header; 0 for the other records.
  std::uint32_t conn = 0;
  std::int64_t time_ns = 0;
};

/// Reads the record whose header starts at `offset` in `buffer`; its fields
/// view `buffer`, which must outlive them.
/// \throws DataError when a length runs past the buffer.
Record RecordIn(std::string_view buffer, std::uint64_t offset);

/// Reads the header of the record at `offset` in `file` (not its data).
/// \throws DataError when a length runs past the file or above the caps.
Record RecordAt(BagFile& file, std::uint64_t offset);

/// One entry of an index data record (bag.py 2778-2800): a message's time
/// and the offset of its record in the chunk's data.
struct IndexDataEntry {
  std::int64_t time_ns = 0;
  std::uint32_t offset = 0;
};

/// The `count` entries of an index data record's data (12 bytes each:
/// u32 sec, u32 nsec, u32 offset).
/// \throws DataError when the data holds fewer.
std::vector<IndexDataEntry> ParseIndexData(std::string_view data, std::uint32_t count);

/// A connection: a topic from one publisher, with its message type.
struct Connection {
  std::uint32_t id = 0;
  std::string topic;
  std::string type;
  std::string md5sum;
};

/// A connection record's header and data (itself "name=value" fields).
Connection ParseConnection(const Record& record, std::string_view data);

}  // namespace mpcal::bag::ros1
