// A ROS 1 bag (format 2.0) copied with its IMU messages edited, written as
// Debian's python3-rosbag 1.15.15 writes one (rosbag/bag.py): the magic and a
// bag header record padded with spaces to 4096 bytes of header and data
// (lines 1687-1695, 1989-1998), rewritten at the end with the index's place
// and counts (1584-1605); each chunk (header fields op, compression, size:
// 1721-1728) followed by one index data record per connection in it (ver 1,
// entries of time and offset into the unpacked chunk: 1731-1746); at the end
// the connection records (1697-1712) and one chunk info record per chunk
// (ver 1, chunk_pos, start and end time, counts per connection: 1748-1766).
// The chunks' records (connections and messages) are copied as they are,
// only the IMU messages' two vectors changed in place; the indexes are made
// from what is written, so a bag that was not closed comes out closed.
#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <type_traits>

#include "bag/bag_io.h"
#include "bag/bag_write.h"
#include "bag/decompress.h"
#include "bag/imu_decode.h"
#include "bag/ros1_bag.h"
#include "bag/ros1_records.h"
#include "mpcal/error.h"

namespace mpcal::bag {
namespace {

using ros1::Record;

constexpr std::size_t kBagHeaderBytes = 4096;

std::string Field(std::string_view name, std::string_view value) {
  std::string out;
  Put(out, static_cast<std::uint32_t>(name.size() + 1 + value.size()));
  out.append(name).append("=").append(value);
  return out;
}
template <typename T>
requires std::is_arithmetic_v<T> std::string Field(std::string_view name, T value) {
  std::string raw;
  Put(raw, value);
  return Field(name, std::string_view(raw));
}
std::string TimeBytes(std::int64_t ns) {
  std::string raw;
  Put(raw, static_cast<std::uint32_t>(ns / 1'000'000'000));
  Put(raw, static_cast<std::uint32_t>(ns % 1'000'000'000));
  return raw;
}
std::string RecordBytes(const std::string& header, std::string_view data) {
  std::string out;
  Put(out, static_cast<std::uint32_t>(header.size()));
  out += header;
  Put(out, static_cast<std::uint32_t>(data.size()));
  out.append(data);
  return out;
}

std::string BagHeader(std::uint64_t index_pos,
                      std::uint32_t conns,
                      std::uint32_t chunks) {
  const std::string header = Field("op", std::uint8_t{ros1::kBagHeader}) +
                             Field("index_pos", index_pos) + Field("conn_count", conns) +
                             Field("chunk_count", chunks);
  return RecordBytes(header, std::string(kBagHeaderBytes - header.size(), ' '));
}

struct IndexEntry {
  std::int64_t time_ns;
  std::uint32_t offset;
};
// Connections in the order their first message comes in the chunk, as
// bag.py's dictionaries keep them (its index data and chunk info records).
struct ChunkInfo {
  std::uint64_t pos = 0;
  std::int64_t start_ns = 0, end_ns = 0;
  std::vector<std::uint32_t> order;
  std::map<std::uint32_t, std::uint32_t> counts;
};

class Ros1Rewriter {
 public:
  Ros1Rewriter(BagFile& file,
               std::ostream& out,
               const std::string& topic,
               const ImuEdit& edit,
               const ImuCovariances& covariances)
      : file_(file), out_(out), topic_(topic), edit_(edit), covariances_(covariances) {}

  // A connection's records must agree (topic, type, md5sum) and come before
  // its messages, as rosbag writes them: the copy's index lists each
  // connection once, and a reader that takes it from there would read a
  // message the walk copied unedited, before the record said its topic, as
  // an IMU message (or, for an id given two topics, the other topic's).
  void Connection(std::string_view raw, const Record& r, std::string_view data) {
    const ros1::Connection c = ros1::ParseConnection(r, data);
    const auto [known, fresh] = defined_.try_emplace(c.id, c);
    const ros1::Connection& first = known->second;
    if (!fresh &&
        (first.topic != c.topic || first.type != c.type || first.md5sum != c.md5sum)) {
      throw DataError("connection " + std::to_string(c.id) + " is given twice, as '" +
                      first.topic + "' (" + first.type + ") and as '" + c.topic + "' (" +
                      c.type + ")");
    }
    if (c.topic == topic_ && undefined_.count(c.id) != 0) {
      throw DataError("a message of connection " + std::to_string(c.id) +
                      " comes before the connection's record (topic '" + c.topic +
                      "'), which rosbag writes first");
    }
    if (c.topic == topic_) {
      if (c.type != kRos1ImuType || c.md5sum != kRos1ImuMd5) {
        throw Error(ErrorKind::kInput,
                    file_.path() + ": topic '" + c.topic + "' is of type " + c.type +
                        " (md5sum " + c.md5sum + "), not sensor_msgs/Imu (md5sum " +
                        std::string(kRos1ImuMd5) + ")");
      }
      imu_.insert(c.id);
    }
    if (connections_.count(c.id) == 0) {
      connections_[c.id] = std::string(raw);
      topics_.push_back({c.topic, c.type, "ros1", 0, 0, 0});
    }
  }

  void Chunk(const Record& r) {
    const std::string compression = ros1::StringField(r.fields, "compression");
    if (!IsKnownCompression(compression) || compression == "zstd") {
      throw DataError("unknown chunk compression '" + compression +
                      "' (a ROS 1 bag has none, bz2 or lz4)");
    }
    if (r.data_length > kBagMaxChunkBytes) throw DataError("a chunk above the size cap");
    std::string contents =
        Decompress(compression,
                   file_.ReadAt(r.data_offset, r.data_length, "the chunk"),
                   ros1::U32Field(r.fields, "size"));
    ChunkInfo info;
    std::map<std::uint32_t, std::vector<IndexEntry>> index;
    for (std::uint64_t at = 0; at < contents.size();) {
      const Record m = ros1::RecordIn(contents, at);
      if (m.op == ros1::kConnection) {
        Connection(std::string_view(contents).substr(at, m.next - at),
                   m,
                   std::string_view(contents).substr(m.data_offset, m.data_length));
      } else if (m.op == ros1::kMessageData) {
        const std::uint32_t conn = m.conn;
        const std::int64_t t = m.time_ns;
        index[conn].push_back({t, static_cast<std::uint32_t>(at)});
        info.start_ns = info.counts.empty() ? t : std::min(info.start_ns, t);
        info.end_ns = info.counts.empty() ? t : std::max(info.end_ns, t);
        if (info.counts.count(conn) == 0) info.order.push_back(conn);
        ++info.counts[conn];
        if (imu_.count(conn) != 0) {
          std::string data = contents.substr(m.data_offset, m.data_length);
          EditImu(data, /*cdr=*/false, t, edit_, covariances_);
          contents.replace(m.data_offset, m.data_length, data);
          ++result_.imu_messages;
        } else {
          if (defined_.count(conn) == 0) undefined_.insert(conn);
          ++result_.other_messages;
        }
      }
      at = m.next;
    }
    compressions_.insert(compression);
    info.pos = out_.pos();
    const std::string header = Field("op", std::uint8_t{ros1::kChunk}) +
                               Field("compression", compression) +
                               Field("size", static_cast<std::uint32_t>(contents.size()));
    out_.Write(RecordBytes(header, Compress(compression, contents)));
    for (const std::uint32_t conn : info.order) {
      const std::vector<IndexEntry>& entries = index[conn];
      std::string data;
      for (const IndexEntry& e : entries) {
        data += TimeBytes(e.time_ns);
        Put(data, e.offset);
      }
      out_.Write(
          RecordBytes(Field("op", std::uint8_t{ros1::kIndexData}) + Field("conn", conn) +
                          Field("ver", std::uint32_t{1}) +
                          Field("count", static_cast<std::uint32_t>(entries.size())),
                      data));
    }
    chunks_.push_back(std::move(info));
  }

  // The connections and chunk infos; returns where they start.
  std::uint64_t Index() {
    const std::uint64_t index_pos = out_.pos();
    for (const auto& [id, raw] : connections_) out_.Write(raw);
    for (const ChunkInfo& c : chunks_) {
      std::string data;
      for (const std::uint32_t conn : c.order)
        Put(data, conn), Put(data, c.counts.at(conn));
      out_.Write(RecordBytes(
          Field("op", std::uint8_t{ros1::kChunkInfo}) + Field("ver", std::uint32_t{1}) +
              Field("chunk_pos", c.pos) + Field("start_time", TimeBytes(c.start_ns)) +
              Field("end_time", TimeBytes(c.end_ns)) +
              Field("count", static_cast<std::uint32_t>(c.counts.size())),
          data));
    }
    return index_pos;
  }

  CountingOut& out() { return out_; }
  std::uint32_t connection_count() const {
    return static_cast<std::uint32_t>(connections_.size());
  }
  std::uint32_t chunk_count() const { return static_cast<std::uint32_t>(chunks_.size()); }
  bool topic_found() const { return !imu_.empty(); }
  const std::vector<BagTopic>& topics() const { return topics_; }
  BagRewriteResult& result() { return result_; }
  const std::set<std::string>& compressions() const { return compressions_; }

 private:
  BagFile& file_;
  CountingOut out_;
  const std::string& topic_;
  const ImuEdit& edit_;
  const ImuCovariances& covariances_;
  std::map<std::uint32_t, std::string> connections_;  // id -> the record's bytes
  std::vector<BagTopic> topics_;
  std::set<std::uint32_t> imu_;
  std::map<std::uint32_t, ros1::Connection> defined_;  // id -> its first record
  std::set<std::uint32_t> undefined_;  // ids with a message before any record
  std::vector<ChunkInfo> chunks_;
  std::set<std::string> compressions_;
  BagRewriteResult result_;
};

std::string At(std::uint64_t offset) { return "byte " + std::to_string(offset); }

// The records after the bag header, in file order.
void Walk(BagFile& file,
          std::uint64_t first,
          bool indexed,
          Ros1Rewriter& w,
          std::vector<std::string>& warnings) {
  for (std::uint64_t offset = first; offset < file.size();) {
    Record r;
    try {
      r = ros1::RecordAt(file, offset);
    } catch (const DataError& e) {
      if (indexed)
        ThrowBagError(file.path(), "record at " + At(offset) + ": " + e.what());
      warnings.push_back(file.path() + ": the file is cut short at " + At(offset) + " (" +
                         e.what() + "); the messages before it are copied");
      return;
    }
    try {
      if (r.op == ros1::kChunk) {
        w.Chunk(r);
      } else if (r.op == ros1::kConnection) {
        if (r.next - offset > kBagMaxRecordBytes)
          throw DataError("a connection record above the size cap");
        const std::string raw = file.ReadAt(offset, r.next - offset, "the connection");
        w.Connection(raw, r, std::string_view(raw).substr(r.data_offset - offset));
      } else if (r.op == ros1::kMessageData) {
        throw DataError(
            "a message outside any chunk (rosbag writes every message in a chunk)");
      }
      // Index data and chunk info records are made afresh for what is written.
    } catch (const DataError& e) {
      ThrowBagError(file.path(),
                    (r.op == ros1::kChunk ? "chunk at " : "record at ") + At(offset) +
                        ": " + e.what());
    }
    offset = r.next;
  }
}

}  // namespace

BagRewriteResult RewriteRos1(const std::string& input,
                             std::ostream& output,
                             const std::string& topic,
                             const ImuEdit& edit,
                             const ImuCovariances& covariances,
                             std::vector<std::string>& warnings) {
  BagFile file(input);
  if (file.ReadSome(0, ros1::kMagic.size()) != ros1::kMagic) {
    ThrowBagError(input, "not a ROS 1 bag of format 2.0");
  }
  Record header;
  try {
    header = ros1::RecordAt(file, ros1::kMagic.size());
    if (header.op != ros1::kBagHeader)
      throw DataError("the first record is not the bag header");
  } catch (const DataError& e) {
    ThrowBagError(input, "bag header at " + At(ros1::kMagic.size()) + ": " + e.what());
  }
  if (header.fields.count("encryptor") != 0) {
    ThrowBagError(input,
                  "an encrypted bag (its messages cannot be read without the key)");
  }
  std::uint64_t index_pos = 0;
  try {
    index_pos = ros1::U64Field(header.fields, "index_pos");
  } catch (const DataError& e) {
    ThrowBagError(input, "bag header: " + std::string(e.what()));
  }
  if (index_pos == 0) {
    warnings.push_back(input +
                       ": the bag has no index (it was not closed); every chunk is "
                       "copied and the bag written is indexed");
  } else if (index_pos >= file.size()) {
    warnings.push_back(input + ": the index at " + At(index_pos) +
                       " lies past the end of the file (it is cut short); every chunk "
                       "is copied and the bag written is indexed");
    index_pos = 0;
  }
  // The header is completed at the end: a stream that cannot seek back
  // (a pipe, a terminal) is refused before any work.
  const std::streampos start = output.tellp();
  if (start < 0) {
    throw Error(ErrorKind::kIo,
                "a ROS 1 bag is written to a file (its header is completed at the end), "
                "not to a pipe or a terminal");
  }
  Ros1Rewriter w(file, output, topic, edit, covariances);
  w.out().Write(ros1::kMagic);
  const std::uint64_t header_at = w.out().pos();
  w.out().Write(BagHeader(0, 0, 0));
  Walk(file, header.next, index_pos != 0, w, warnings);
  if (!w.topic_found()) {
    throw Error(
        ErrorKind::kInput,
        input + ": no topic '" + topic + "'; the bag holds " + ListTopics(w.topics()));
  }
  const std::uint64_t index_at = w.Index();
  output.seekp(start + static_cast<std::streamoff>(header_at));
  w.out().Write(BagHeader(index_at, w.connection_count(), w.chunk_count()));
  output.seekp(0, std::ios_base::end);
  if (!output) throw Error(ErrorKind::kIo, "the bag's header could not be completed");
  BagRewriteResult result = w.result();
  result.format = BagFormat::kRos1;
  result.compressions.assign(w.compressions().begin(), w.compressions().end());
  return result;
}

}  // namespace mpcal::bag
