// MCAP: the walk over the data section in file order (mcap_records.h cites
// the specification). The summary section, when the footer points at one,
// gives the channels and the chunk indexes up front, so a chunk without a
// message of the topic is skipped unread; without it (a file cut short has
// no footer) every chunk is unpacked, and what precedes the cut is kept.
#include "bag/mcap_bag.h"

#include <algorithm>
#include <functional>
#include <map>
#include <set>

#include "bag/bag_io.h"
#include "bag/decompress.h"
#include "bag/imu_decode.h"
#include "bag/mcap_records.h"
#include "bag/ros1_bag.h"
#include "mpcal/error.h"

namespace mpcal::bag {
namespace {

using namespace mcap;  // NOLINT(google-build-using-namespace): the records' names

std::string At(std::uint64_t offset) { return "byte " + std::to_string(offset); }

struct Opened {
  bool complete = false;  // a footer and the closing magic
  std::uint64_t data_end = 0;
  std::map<std::uint16_t, Schema> schemas;
  std::map<std::uint16_t, Channel> channels;
  std::map<std::uint64_t, ChunkIndex> chunk_indexes;
};

struct Visitor {
  std::function<bool(std::uint64_t chunk_offset)> open_chunk;
  std::function<void(const std::string& compression)> on_chunk;
  std::function<void(const Schema&)> on_schema;
  std::function<void(const Channel&)> on_channel;
  std::function<void(const Message&)> on_message;
  std::function<void(std::string_view body)> on_message_index;
};

constexpr std::uint64_t kFooterBytes = 1 + 8 + 20;

void ReadSummary(BagFile& file, std::uint64_t begin, std::uint64_t end, Opened& opened) {
  for (std::uint64_t offset = begin; offset < end;) {
    const RecordSpan r = RecordAt(file, offset);
    if (r.next > end) throw DataError("a summary record runs past the footer");
    if (r.body_length > kBagMaxRecordBytes)
      throw DataError("a summary record above the cap");
    const std::string body =
        file.ReadAt(r.body_offset, r.body_length, "a summary record");
    if (r.op == kSchema) {
      const Schema s = ParseSchema(body);
      opened.schemas[s.id] = s;
    } else if (r.op == kChannel) {
      const Channel c = ParseChannel(body);
      opened.channels[c.id] = c;
    } else if (r.op == kChunkIndex) {
      const ChunkIndex ci = ParseChunkIndex(body);
      opened.chunk_indexes[ci.chunk_start_offset] = ci;
    }
    offset = r.next;
  }
}

Opened Open(BagFile& file, std::vector<std::string>& warnings) {
  if (file.ReadSome(0, kMagic.size()) != kMagic) {
    ThrowBagError(file.path(),
                  "not an MCAP file (it does not start with the MCAP magic)");
  }
  Opened opened;
  opened.data_end = file.size();
  const std::uint64_t tail = kFooterBytes + kMagic.size();
  if (file.size() >= 2 * kMagic.size() + tail - kMagic.size()) {
    const std::uint64_t footer_at = file.size() - tail;
    const std::string footer = file.ReadAt(footer_at, tail, "the footer");
    ByteCursor c(footer);
    const bool is_footer = c.U8("op") == kFooter && c.U64("length") == 20;
    const std::uint64_t summary_start = c.U64("summary_start");
    c.U64("summary_offset_start");
    c.U32("summary_crc");
    if (is_footer && c.Bytes(kMagic.size(), "magic") == kMagic) {
      opened.complete = true;
      opened.data_end = footer_at;
      if (summary_start != 0 && summary_start >= kMagic.size() &&
          summary_start < footer_at) {
        opened.data_end = summary_start;
        try {
          ReadSummary(file, summary_start, footer_at, opened);
        } catch (const DataError& e) {
          warnings.push_back(file.path() + ": the summary at " + At(summary_start) +
                             " cannot be read (" + e.what() +
                             "); every chunk is read instead");
          opened.channels.clear(), opened.chunk_indexes.clear();
        }
      }
    }
  }
  if (!opened.complete) {
    warnings.push_back(file.path() +
                       ": the file has no footer (it is cut short or was not "
                       "closed); the records it holds are read in order");
  }
  return opened;
}

void WalkChunk(std::string_view records, const Visitor& v) {
  for (std::uint64_t offset = 0; offset < records.size();) {
    const RecordSpan r = RecordIn(records, offset);
    const std::string_view body = records.substr(r.body_offset, r.body_length);
    if (r.op == kSchema && v.on_schema) v.on_schema(ParseSchema(body));
    if (r.op == kChannel && v.on_channel) v.on_channel(ParseChannel(body));
    if (r.op == kMessage && v.on_message) v.on_message(ParseMessage(body));
    offset = r.next;
  }
}

// A chunk as read and as unpacked, kept from one chunk to the next: a fresh
// megabyte buffer for each would be mapped, faulted in page by page and
// returned to the system again.
struct ChunkBuffers {
  ByteBuffer body;
  ByteBuffer unpacked;
};

void VisitChunk(BagFile& file,
                std::uint64_t offset,
                const RecordSpan& r,
                const Visitor& v,
                ChunkBuffers& buffers) {
  // The fixed fields and the compression's length come before anything large.
  const std::string fixed = file.ReadAt(
      r.body_offset, std::min<std::uint64_t>(r.body_length, 32), "the chunk header");
  ByteCursor head(fixed);
  head.Skip(28, "the chunk header");
  const std::uint32_t name_length = head.U32("the compression's length");
  if (name_length > kBagMaxFieldBytes)
    throw DataError("a compression name above the cap");
  const std::string compression =
      file.ReadAt(r.body_offset + 32, name_length, "the compression");
  if (v.on_chunk) v.on_chunk(compression);
  if (!IsKnownCompression(compression) || compression == "bz2" || compression == "none") {
    throw DataError("unknown chunk compression '" + compression +
                    "' (an MCAP chunk has none, lz4 or zstd)");
  }
  if (v.open_chunk && !v.open_chunk(offset)) return;
  if (r.body_length > kBagMaxChunkBytes) throw DataError("a chunk above the size cap");
  const ChunkHeader h =
      ParseChunk(file.ReadInto(r.body_offset, r.body_length, "the chunk", buffers.body));
  // A chunk with a CRC (0 means none) is checked once, by it, below.
  const std::string_view records = Decompress(h.compression,
                                              h.records,
                                              h.uncompressed_size,
                                              buffers.unpacked,
                                              h.uncompressed_crc != 0);
  if (h.uncompressed_crc != 0 && Crc32(records) != h.uncompressed_crc) {
    throw DataError("the CRC-32 of the unpacked records does not match the chunk's");
  }
  WalkChunk(records, v);
}

// Returns false at the end of the data section.
bool VisitRecord(BagFile& file,
                 std::uint64_t offset,
                 const RecordSpan& r,
                 const Visitor& v,
                 ChunkBuffers& buffers) {
  if (r.op == kDataEnd || r.op == kFooter) return false;
  if (r.op == kChunk) {
    VisitChunk(file, offset, r, v, buffers);
    return true;
  }
  if (r.op != kSchema && r.op != kChannel && r.op != kMessage && r.op != kMessageIndex) {
    return true;
  }
  if (r.body_length > kBagMaxRecordBytes) throw DataError("a record above the size cap");
  const std::string body = file.ReadAt(r.body_offset, r.body_length, "the record");
  if (r.op == kSchema && v.on_schema) v.on_schema(ParseSchema(body));
  if (r.op == kChannel && v.on_channel) v.on_channel(ParseChannel(body));
  if (r.op == kMessage && v.on_message) v.on_message(ParseMessage(body));
  if (r.op == kMessageIndex && v.on_message_index) v.on_message_index(body);
  return true;
}

void Walk(BagFile& file,
          const Opened& opened,
          const Visitor& v,
          std::vector<std::string>& warnings) {
  ChunkBuffers buffers;
  for (std::uint64_t offset = kMagic.size(); offset < opened.data_end;) {
    RecordSpan r;
    try {
      r = RecordAt(file, offset);
      if (r.next > opened.data_end)
        throw DataError("the record runs past the data section");
    } catch (const DataError& e) {
      if (opened.complete)
        ThrowBagError(file.path(), "record at " + At(offset) + ": " + e.what());
      warnings.push_back(file.path() + ": the file is cut short at " + At(offset) + " (" +
                         e.what() + "); the messages before it are read");
      return;
    }
    try {
      if (!VisitRecord(file, offset, r, v, buffers)) return;
    } catch (const DataError& e) {
      ThrowBagError(
          file.path(),
          (r.op == kChunk ? "chunk at " : "record at ") + At(offset) + ": " + e.what());
    }
    offset = r.next;
  }
}

std::string TypeOf(const Opened& opened,
                   const std::map<std::uint16_t, Schema>& schemas,
                   const Channel& c) {
  auto it = schemas.find(c.schema_id);
  if (it != schemas.end()) return it->second.name;
  it = opened.schemas.find(c.schema_id);
  return it != opened.schemas.end() ? it->second.name : std::string("(no schema)");
}

void CheckImu(const std::string& path, const Channel& c, const std::string& type) {
  const bool ok = (c.message_encoding == "cdr" && type == kRos2ImuType) ||
                  (c.message_encoding == "ros1" && type == kRos1ImuType);
  if (!ok) {
    throw Error(ErrorKind::kInput,
                path + ": topic '" + c.topic + "' holds " + type + " in encoding '" +
                    c.message_encoding + "', not sensor_msgs/msg/Imu in 'cdr' or " +
                    "sensor_msgs/Imu in 'ros1'");
  }
}

}  // namespace

void ReadMcapImu(const std::string& path,
                 const std::string& topic,
                 const ImuSink& sink,
                 std::vector<std::string>& warnings) {
  BagFile file(path);
  const Opened opened = Open(file, warnings);
  std::map<std::uint16_t, Schema> schemas = opened.schemas;
  std::map<std::uint16_t, Channel> seen = opened.channels;
  std::map<std::uint16_t, bool> ids;  // channel id -> CDR (else ROS 1)
  const auto take = [&](const Channel& c) {
    if (c.topic != topic) return;
    CheckImu(path, c, TypeOf(opened, schemas, c));
    ids[c.id] = c.message_encoding == "cdr";
  };
  for (const auto& [id, c] : seen) take(c);
  const auto topics = [&] {
    std::vector<BagTopic> list;
    list.reserve(seen.size());
    for (const auto& [id, c] : seen) {
      list.push_back({c.topic, TypeOf(opened, schemas, c), c.message_encoding, 0, 0, 0});
    }
    return ListTopics(list);
  };
  if (!opened.chunk_indexes.empty() && ids.empty()) {
    throw Error(ErrorKind::kInput,
                path + ": no topic '" + topic + "'; the file holds " + topics());
  }
  ImuBatcher batcher(sink);
  Visitor v;
  v.open_chunk = [&](std::uint64_t offset) {
    const auto it = opened.chunk_indexes.find(offset);
    if (it == opened.chunk_indexes.end() || it->second.message_index_offsets.empty())
      return true;
    for (const auto& [id, cdr] : ids) {
      if (it->second.message_index_offsets.count(id) != 0) return true;
    }
    return false;
  };
  v.on_schema = [&](const Schema& s) { schemas[s.id] = s; };
  v.on_channel = [&](const Channel& c) {
    take(c);
    seen.insert_or_assign(c.id, c);
  };
  v.on_message = [&](const Message& m) {
    const auto it = ids.find(m.channel_id);
    if (it == ids.end()) return;
    const auto t = static_cast<std::int64_t>(m.log_time_ns);
    batcher.Add(it->second ? DecodeCdrImu(m.data, t) : DecodeRos1Imu(m.data, t));
  };
  Walk(file, opened, v, warnings);
  batcher.Flush();
  if (ids.empty()) {
    throw Error(ErrorKind::kInput,
                path + ": no topic '" + topic + "'; the file holds " + topics());
  }
  if (batcher.count() == 0)
    warnings.push_back(path + ": topic '" + topic + "' holds no message");
}

BagSummary InspectMcap(const std::string& path) {
  BagSummary summary;
  summary.format = BagFormat::kMcap;
  BagFile file(path);
  const Opened opened = Open(file, summary.warnings);
  std::map<std::uint16_t, Schema> schemas = opened.schemas;
  std::map<std::uint16_t, Channel> channels = opened.channels;
  struct Stats {
    std::int64_t count = 0, first = 0, last = 0;
  };
  std::map<std::uint16_t, Stats> stats;
  std::set<std::string> compressions;
  bool chunk_opened = false;
  Visitor v;
  v.open_chunk = [&](std::uint64_t offset) {
    const auto it = opened.chunk_indexes.find(offset);
    // Counted from the Message Index records that follow it when it has them.
    chunk_opened =
        it == opened.chunk_indexes.end() || it->second.message_index_offsets.empty();
    return chunk_opened;
  };
  v.on_chunk = [&](const std::string& c) { compressions.insert(c.empty() ? "none" : c); };
  v.on_schema = [&](const Schema& s) { schemas[s.id] = s; };
  v.on_channel = [&](const Channel& c) { channels.insert_or_assign(c.id, c); };
  v.on_message = [&](const Message& m) {
    Stats& s = stats[m.channel_id];
    const auto t = static_cast<std::int64_t>(m.log_time_ns);
    s.first = s.count == 0 ? t : std::min(s.first, t);
    s.last = s.count == 0 ? t : std::max(s.last, t);
    ++s.count;
  };
  v.on_message_index = [&](std::string_view body) {
    if (chunk_opened) return;
    Stats part;
    const std::uint16_t id = ParseMessageIndex(body, part.count, part.first, part.last);
    if (part.count == 0) return;
    Stats& s = stats[id];
    s.first = s.count == 0 ? part.first : std::min(s.first, part.first);
    s.last = s.count == 0 ? part.last : std::max(s.last, part.last);
    s.count += part.count;
  };
  Walk(file, opened, v, summary.warnings);
  for (const auto& [id, c] : channels) {
    const Stats s = stats.count(id) != 0 ? stats[id] : Stats{};
    summary.topics.push_back({c.topic,
                              TypeOf(opened, schemas, c),
                              c.message_encoding,
                              s.count,
                              s.first,
                              s.last});
  }
  summary.compressions.assign(compressions.begin(), compressions.end());
  return summary;
}

}  // namespace mpcal::bag
