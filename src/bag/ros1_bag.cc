// ROS 1 bags, format 2.0: the walk over the file's records (ros1_records.h
// cites the layout's source). The top-level records are walked in file
// order; a chunk is unpacked only when the index (chunk info records, read
// first) says it holds a message of the topic, or when there is no index
// (a recording that was not closed), then every chunk is. A chunk stored
// without compression is read only where the index puts the topic's
// messages, when they are a small part of it (ros1_indexed_read.h).
#include "bag/ros1_bag.h"

#include <functional>
#include <map>
#include <set>

#include "bag/bag_io.h"
#include "bag/decompress.h"
#include "bag/imu_decode.h"
#include "bag/ros1_indexed_read.h"
#include "bag/ros1_records.h"
#include "mpcal/error.h"

namespace mpcal::bag {
namespace {

using ros1::Connection;
using ros1::Record;

struct Index {
  bool usable = false;
  std::map<std::uint32_t, Connection> connections;
  /// chunk position -> connection id -> messages in the chunk
  std::map<std::uint64_t, std::map<std::uint32_t, std::uint32_t>> chunks;
};

struct Visitor {
  std::function<bool(std::uint64_t chunk_pos)> open_chunk;
  std::function<void(const Connection&)> on_connection;
  std::function<void(const Record&, std::string_view data)> on_message;
  std::function<void(const Record&, std::string_view data)> on_index;
  std::function<void(const std::string& compression)> on_chunk;
  /// A chunk stored without compression: true when it was read through the
  /// index (ros1_indexed_read.h), false to have it walked whole.
  std::function<bool(std::uint64_t chunk_pos, const Record& chunk)> read_stored;
};

std::string At(std::uint64_t offset) { return "byte " + std::to_string(offset); }

// The bag header record; the first record after it; the index if usable.
struct Opened {
  std::uint64_t first_record = 0;
  Index index;
};

Index ReadIndex(BagFile& file,
                std::uint64_t pos,
                std::uint32_t connections,
                std::uint32_t chunks) {
  Index index;
  for (std::uint32_t i = 0; i < connections; ++i) {
    const Record r = ros1::RecordAt(file, pos);
    if (r.op != ros1::kConnection) throw DataError("a record other than a connection");
    const Connection c = ros1::ParseConnection(
        r, file.ReadAt(r.data_offset, r.data_length, "connection data"));
    index.connections[c.id] = c;
    pos = r.next;
  }
  for (std::uint32_t i = 0; i < chunks; ++i) {
    const Record r = ros1::RecordAt(file, pos);
    if (r.op != ros1::kChunkInfo) throw DataError("a record other than a chunk info");
    if (ros1::U32Field(r.fields, "ver") != 1)
      throw DataError("chunk info version other than 1");
    const std::string bytes =
        file.ReadAt(r.data_offset, r.data_length, "chunk info data");
    ByteCursor data(bytes);
    auto& counts = index.chunks[ros1::U64Field(r.fields, "chunk_pos")];
    const std::uint32_t n = ros1::U32Field(r.fields, "count");
    for (std::uint32_t k = 0; k < n; ++k) {
      const std::uint32_t conn = data.U32("a connection id");
      counts[conn] += data.U32("a message count");
    }
    pos = r.next;
  }
  index.usable = true;
  return index;
}

Opened Open(BagFile& file, std::vector<std::string>& warnings) {
  const std::string magic = file.ReadSome(0, ros1::kMagic.size());
  if (magic != ros1::kMagic) {
    ThrowBagError(file.path(),
                  "not a ROS 1 bag of format 2.0 (it does not start with "
                  "'#ROSBAG V2.0')");
  }
  Opened opened;
  Record header;
  try {
    header = ros1::RecordAt(file, ros1::kMagic.size());
    if (header.op != ros1::kBagHeader)
      throw DataError("the first record is not the bag header");
  } catch (const DataError& e) {
    ThrowBagError(file.path(),
                  "bag header at " + At(ros1::kMagic.size()) + ": " + e.what());
  }
  if (header.fields.count("encryptor") != 0) {
    ThrowBagError(file.path(),
                  "an encrypted bag (its messages cannot be read without the key)");
  }
  opened.first_record = header.next;
  std::uint64_t index_pos = 0;
  try {
    index_pos = ros1::U64Field(header.fields, "index_pos");
    if (index_pos != 0) {
      opened.index = ReadIndex(file,
                               index_pos,
                               ros1::U32Field(header.fields, "conn_count"),
                               ros1::U32Field(header.fields, "chunk_count"));
    }
  } catch (const DataError& e) {
    warnings.push_back(file.path() + ": the index at " + At(index_pos) +
                       " cannot be read (" + e.what() + "); every chunk is read instead");
  }
  if (index_pos == 0) {
    warnings.push_back(file.path() +
                       ": the bag has no index (it was not closed); every "
                       "chunk is read");
  }
  return opened;
}

void WalkChunk(std::string_view contents, const Visitor& v) {
  std::uint64_t offset = 0;
  while (offset < contents.size()) {
    const Record r = ros1::RecordIn(contents, offset);
    const std::string_view data(contents.data() + r.data_offset, r.data_length);
    if (r.op == ros1::kConnection && v.on_connection) {
      v.on_connection(ros1::ParseConnection(r, data));
    } else if (r.op == ros1::kMessageData && v.on_message) {
      v.on_message(r, data);
    }
    offset = r.next;
  }
}

std::string RecordData(BagFile& file, const Record& r) {
  if (r.data_length > kBagMaxRecordBytes) {
    throw DataError("a record of " + std::to_string(r.data_length) +
                    " bytes is above the cap of " + std::to_string(kBagMaxRecordBytes));
  }
  return file.ReadAt(r.data_offset, r.data_length, "the record data");
}

// A chunk as read and as unpacked, kept from one chunk to the next: a fresh
// megabyte buffer for each would be mapped, faulted in page by page and
// returned to the system again.
struct ChunkBuffers {
  ByteBuffer packed;
  ByteBuffer unpacked;
};

void VisitRecord(BagFile& file,
                 std::uint64_t offset,
                 const Record& r,
                 const Visitor& v,
                 ChunkBuffers& buffers) {
  switch (r.op) {
    case ros1::kChunk: {
      const std::string compression = ros1::StringField(r.fields, "compression");
      if (v.on_chunk) v.on_chunk(compression);
      if (!IsKnownCompression(compression) || compression == "zstd") {
        throw DataError("unknown chunk compression '" + compression +
                        "' (a ROS 1 bag has none, bz2 or lz4)");
      }
      if (v.open_chunk && !v.open_chunk(offset)) return;
      if (compression == "none" && v.read_stored && v.read_stored(offset, r)) return;
      if (r.data_length > kBagMaxChunkBytes)
        throw DataError("a chunk above the size cap");
      WalkChunk(Decompress(compression,
                           file.ReadInto(
                               r.data_offset, r.data_length, "the chunk", buffers.packed),
                           ros1::U32Field(r.fields, "size"),
                           buffers.unpacked),
                v);
      return;
    }
    case ros1::kConnection:
      if (v.on_connection) v.on_connection(ros1::ParseConnection(r, RecordData(file, r)));
      return;
    case ros1::kMessageData:
      if (v.on_message) v.on_message(r, RecordData(file, r));
      return;
    case ros1::kIndexData:
      if (v.on_index) v.on_index(r, RecordData(file, r));
      return;
    default:
      return;
  }
}

// Walks the top-level records. Without a usable index a record running past
// the end is a file cut short: a warning, and what came before is kept.
void Walk(BagFile& file,
          const Opened& opened,
          const Visitor& v,
          std::vector<std::string>& warnings) {
  std::uint64_t offset = opened.first_record;
  ChunkBuffers buffers;
  while (offset < file.size()) {
    Record r;
    try {
      r = ros1::RecordAt(file, offset);
    } catch (const DataError& e) {
      if (opened.index.usable)
        ThrowBagError(file.path(), "record at " + At(offset) + ": " + e.what());
      warnings.push_back(file.path() + ": the file is cut short at " + At(offset) + " (" +
                         e.what() + "); the messages before it are read");
      return;
    }
    try {
      VisitRecord(file, offset, r, v, buffers);
    } catch (const DataError& e) {
      ThrowBagError(file.path(),
                    (r.op == ros1::kChunk ? "chunk at " : "record at ") + At(offset) +
                        ": " + e.what());
    }
    offset = r.next;
  }
}

void CheckImu(const std::string& path, const Connection& c) {
  if (c.type != kRos1ImuType || c.md5sum != kRos1ImuMd5) {
    throw Error(ErrorKind::kInput,
                path + ": topic '" + c.topic + "' is of type " + c.type + " (md5sum " +
                    c.md5sum + "), not sensor_msgs/Imu (md5sum " +
                    std::string(kRos1ImuMd5) + ")");
  }
}

std::vector<BagTopic> TopicsOf(const std::map<std::uint32_t, Connection>& connections) {
  std::vector<BagTopic> topics;
  for (const auto& [id, c] : connections) {
    bool found = false;
    for (const BagTopic& t : topics) found = found || t.name == c.topic;
    if (!found) topics.push_back({c.topic, c.type, "ros1", 0, 0, 0});
  }
  return topics;
}

}  // namespace

std::string ListTopics(const std::vector<BagTopic>& topics) {
  if (topics.empty()) return "none";
  std::string out;
  for (const BagTopic& t : topics) {
    out += (out.empty() ? "" : ", ") + t.name + " (" + t.type + ")";
  }
  return out;
}

void ReadRos1Imu(const std::string& path,
                 const std::string& topic,
                 const ImuSink& sink,
                 std::vector<std::string>& warnings) {
  BagFile file(path);
  const Opened opened = Open(file, warnings);
  std::map<std::uint32_t, Connection> seen = opened.index.connections;
  std::set<std::uint32_t> ids;
  for (const auto& [id, c] : seen) {
    if (c.topic == topic) {
      CheckImu(path, c);
      ids.insert(id);
    }
  }
  if (opened.index.usable && ids.empty()) {
    throw Error(
        ErrorKind::kInput,
        path + ": no topic '" + topic + "'; the bag holds " + ListTopics(TopicsOf(seen)));
  }
  ImuBatcher batcher(sink);
  Visitor v;
  v.open_chunk = [&](std::uint64_t pos) {
    if (!opened.index.usable) return true;
    const auto it = opened.index.chunks.find(pos);
    if (it == opened.index.chunks.end()) return true;
    for (const auto& [conn, count] : it->second) {
      if (count > 0 && ids.count(conn) != 0) return true;
    }
    return false;
  };
  v.on_connection = [&](const Connection& c) {
    if (c.topic == topic) {
      CheckImu(path, c);
      ids.insert(c.id);
    }
    seen.insert_or_assign(c.id, c);
  };
  v.on_message = [&](const Record& r, std::string_view data) {
    if (ids.count(r.conn) == 0) return;
    batcher.Add(DecodeRos1Imu(data, r.time_ns));
  };
  ByteBuffer indexed;
  v.read_stored = [&](std::uint64_t pos, const Record& chunk) {
    const auto it = opened.index.chunks.find(pos);
    if (!opened.index.usable || it == opened.index.chunks.end()) return false;
    std::uint64_t expected = 0;
    for (const auto& [conn, count] : it->second) {
      if (ids.count(conn) != 0) expected += count;
    }
    return ros1::ReadIndexedMessages(file, chunk, ids, expected, v.on_message, indexed);
  };
  Walk(file, opened, v, warnings);
  batcher.Flush();
  if (ids.empty()) {
    throw Error(
        ErrorKind::kInput,
        path + ": no topic '" + topic + "'; the bag holds " + ListTopics(TopicsOf(seen)));
  }
  if (batcher.count() == 0)
    warnings.push_back(path + ": topic '" + topic + "' holds no message");
}

BagSummary InspectRos1(const std::string& path) {
  BagSummary summary;
  summary.format = BagFormat::kRos1;
  BagFile file(path);
  const Opened opened = Open(file, summary.warnings);
  std::map<std::uint32_t, Connection> connections = opened.index.connections;
  struct Stats {
    std::int64_t count = 0, first = 0, last = 0;
    void Add(std::int64_t t) {
      first = count == 0 ? t : std::min(first, t);
      last = count == 0 ? t : std::max(last, t);
      ++count;
    }
  };
  std::map<std::uint32_t, Stats> stats;
  std::set<std::string> compressions;
  Visitor v;
  v.open_chunk = [&](std::uint64_t) { return !opened.index.usable; };
  v.on_chunk = [&](const std::string& c) { compressions.insert(c); };
  v.on_connection = [&](const Connection& c) { connections.insert_or_assign(c.id, c); };
  v.on_message = [&](const Record& r, std::string_view) { stats[r.conn].Add(r.time_ns); };
  v.on_index = [&](const Record& r, std::string_view data) {
    if (!opened.index.usable) return;
    Stats& s = stats[ros1::U32Field(r.fields, "conn")];
    for (const ros1::IndexDataEntry& e :
         ros1::ParseIndexData(data, ros1::U32Field(r.fields, "count"))) {
      s.Add(e.time_ns);
    }
  };
  Walk(file, opened, v, summary.warnings);
  summary.topics = TopicsOf(connections);
  for (BagTopic& t : summary.topics) {
    Stats all;
    for (const auto& [id, c] : connections) {
      if (c.topic != t.name || stats.count(id) == 0) continue;
      const Stats& s = stats[id];
      if (s.count == 0) continue;
      all.first = all.count == 0 ? s.first : std::min(all.first, s.first);
      all.last = all.count == 0 ? s.last : std::max(all.last, s.last);
      all.count += s.count;
    }
    t.messages = all.count, t.first_ns = all.first, t.last_ns = all.last;
  }
  summary.compressions.assign(compressions.begin(), compressions.end());
  return summary;
}

}  // namespace mpcal::bag
