#include "bag/mcap_records.h"

#include <algorithm>

#include "mpcal/bag.h"

namespace mpcal::bag::mcap {

RecordSpan RecordIn(std::string_view buffer, std::uint64_t offset) {
  ByteCursor c(buffer);
  c.Skip(offset, "the record start");
  RecordSpan r;
  r.op = c.U8("the opcode");
  r.body_length = c.U64("the record length");
  r.body_offset = c.offset();
  c.Skip(r.body_length, "the record");
  r.next = c.offset();
  return r;
}

RecordSpan RecordAt(BagFile& file, std::uint64_t offset) {
  const std::string head = file.ReadAt(offset, 9, "the record's opcode and length");
  ByteCursor c(head);
  RecordSpan r;
  r.op = c.U8("the opcode");
  r.body_length = c.U64("the record length");
  r.body_offset = offset + 9;
  if (r.body_length > file.size() - r.body_offset) {
    throw DataError("the record needs " + std::to_string(r.body_length) +
                    " bytes but the file has " +
                    std::to_string(file.size() - r.body_offset) + " left");
  }
  r.next = r.body_offset + r.body_length;
  return r;
}

std::string String(ByteCursor& c, const char* what) {
  const std::uint32_t n = c.U32(what);
  if (n > kBagMaxFieldBytes) throw DataError(std::string(what) + " above the length cap");
  return std::string(c.Bytes(n, what));
}

Schema ParseSchema(std::string_view body) {
  ByteCursor c(body);
  Schema s;
  s.id = c.U16("the schema id");
  s.name = String(c, "the schema name");
  s.encoding = String(c, "the schema encoding");
  return s;
}

Channel ParseChannel(std::string_view body) {
  ByteCursor c(body);
  Channel ch;
  ch.id = c.U16("the channel id");
  ch.schema_id = c.U16("the schema id");
  ch.topic = String(c, "the topic");
  ch.message_encoding = String(c, "the message encoding");
  return ch;
}

Message ParseMessage(std::string_view body) {
  ByteCursor c(body);
  Message m;
  m.channel_id = c.U16("the channel id");
  c.U32("the sequence");
  m.log_time_ns = c.U64("log_time");
  c.U64("publish_time");
  m.data = c.Bytes(c.remaining(), "the message data");
  return m;
}

ChunkHeader ParseChunk(std::string_view body) {
  ByteCursor c(body);
  ChunkHeader h;
  c.U64("message_start_time");
  c.U64("message_end_time");
  h.uncompressed_size = c.U64("uncompressed_size");
  h.uncompressed_crc = c.U32("uncompressed_crc");
  h.compression = String(c, "the compression");
  h.records = c.Bytes(c.U64("the records' length"), "the chunk's records");
  return h;
}

ChunkIndex ParseChunkIndex(std::string_view body) {
  ByteCursor c(body);
  ChunkIndex index;
  c.U64("message_start_time");
  c.U64("message_end_time");
  index.chunk_start_offset = c.U64("chunk_start_offset");
  c.U64("chunk_length");
  ByteCursor map(
      c.Bytes(c.U32("the message index offsets' length"), "message_index_offsets"));
  while (!map.empty()) {
    const std::uint16_t channel = map.U16("a channel id");
    index.message_index_offsets[channel] = map.U64("a message index offset");
  }
  return index;
}

std::map<std::uint16_t, std::uint64_t> ParseStatisticsCounts(std::string_view body) {
  ByteCursor c(body);
  c.Skip(8 + 2 + 4 + 4 + 4 + 4 + 8 + 8, "the statistics' counts and times");
  ByteCursor map(c.Bytes(c.U32("the channel counts' length"), "channel_message_counts"));
  std::map<std::uint16_t, std::uint64_t> counts;
  while (!map.empty()) {
    const std::uint16_t channel = map.U16("a channel id");
    counts[channel] = map.U64("a message count");
  }
  return counts;
}

std::uint16_t ParseMessageIndex(std::string_view body,
                                std::int64_t& count,
                                std::int64_t& first_ns,
                                std::int64_t& last_ns) {
  ByteCursor c(body);
  const std::uint16_t channel = c.U16("the channel id");
  ByteCursor entries(c.Bytes(c.U32("the entries' length"), "the entries"));
  while (!entries.empty()) {
    const auto t = static_cast<std::int64_t>(entries.U64("a log time"));
    entries.U64("an offset");
    first_ns = count == 0 ? t : std::min(first_ns, t);
    last_ns = count == 0 ? t : std::max(last_ns, t);
    ++count;
  }
  return channel;
}

}  // namespace mpcal::bag::mcap
