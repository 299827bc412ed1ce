// Private to src/bag/: the messages of some connections read out of a ROS 1
// chunk stored without compression at the offsets its index lists, rather
// than the whole chunk. In a recording where the IMU shares its chunks with
// camera images, a recorder's chunk holds a few images and the forty IMU
// messages that came with them: the IMU's records are a few percent of the
// bytes, and reading only them reads a few percent of the file.
//
// After each chunk a writer puts one index data record per connection in it
// (rosbag/bag.py in Debian's python3-rosbag 1.15.15+ds-2,
// _write_connection_index_record, lines 1731-1745; read back by
// read_connection_index_record, 2778-2800): header fields op=0x04, ver=1,
// conn and count; data, count entries of the message record's time (u32
// sec, u32 nsec) and its offset (u32) in the chunk's data.
#pragma once

#include <cstdint>
#include <functional>
#include <set>
#include <string_view>

#include "bag/bag_io.h"
#include "bag/ros1_records.h"

namespace mpcal::bag::ros1 {

using MessageRecordHandler = std::function<void(const Record&, std::string_view data)>;

/// Hands `on_message` the message records of the connections `ids` in the
/// chunk record `chunk` (its compression none; `expected` messages of those
/// connections by the bag's chunk info), in the chunk's order, each read at
/// the offset its index entry gives and checked against the entry (a message
/// record, of that connection, at that time). Returns false, having handed
/// over nothing, when the index data records after the chunk do not list
/// `expected` entries, or when those records fill so much of the chunk that
/// reading it whole costs less; the caller then walks the chunk.
/// \throws DataError when an entry does not match the record at its offset
///   or runs past the chunk.
bool ReadIndexedMessages(BagFile& file,
                         const Record& chunk,
                         const std::set<std::uint32_t>& ids,
                         std::uint64_t expected,
                         const MessageRecordHandler& on_message,
                         ByteBuffer& buffer);

}  // namespace mpcal::bag::ros1
