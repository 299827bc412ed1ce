// Private to src/bag/: the records of an MCAP file.
//
// Layout from the MCAP specification, foxglove/mcap website/docs/spec/index.md
// (commit 95d0673564eac0b27fd9a8616083fdd47c4c2ec7): the file structure at
// lines 22-36, magic 38-46, the record framing (u8 opcode, u64 length) at
// 114-132, Schema 151-164, Channel 166-180, Message 182-194, Chunk 196-209,
// Chunk Index 224-240, Footer 141-149, Statistics 304-318 and the
// serialisation of strings, maps and arrays at 334-416.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <string_view>

#include "bag/bag_io.h"

namespace mpcal::bag::mcap {

inline constexpr std::string_view kMagic{"\x89MCAP0\r\n", 8};

enum Op : std::uint8_t {
  kHeader = 0x01,
  kFooter = 0x02,
  kSchema = 0x03,
  kChannel = 0x04,
  kMessage = 0x05,
  kChunk = 0x06,
  kMessageIndex = 0x07,
  kChunkIndex = 0x08,
  kStatistics = 0x0B,
  kDataEnd = 0x0F,
};

/// A record's place: its opcode and where its body lies in the buffer or
/// file it was read from.
struct RecordSpan {
  std::uint8_t op = 0;
  std::uint64_t body_offset = 0;
  std::uint64_t body_length = 0;
  std::uint64_t next = 0;
};

/// The record whose opcode is at `offset` in `buffer`.
/// \throws DataError when its length runs past the buffer.
RecordSpan RecordIn(std::string_view buffer, std::uint64_t offset);
/// The record whose opcode is at `offset` in `file` (the body is not read).
/// \throws DataError when its length runs past the file.
RecordSpan RecordAt(BagFile& file, std::uint64_t offset);

std::string String(ByteCursor& c, const char* what);

struct Schema {
  std::uint16_t id = 0;
  std::string name;
  std::string encoding;
};
struct Channel {
  std::uint16_t id = 0;
  std::uint16_t schema_id = 0;
  std::string topic;
  std::string message_encoding;
};
struct Message {
  std::uint16_t channel_id = 0;
  std::uint64_t log_time_ns = 0;
  std::string_view data;
};
struct ChunkHeader {
  std::uint64_t uncompressed_size = 0;
  std::uint32_t uncompressed_crc = 0;
  std::string compression;
  /// The compressed records, within the body given to ParseChunk.
  std::string_view records;
};
struct ChunkIndex {
  std::uint64_t chunk_start_offset = 0;
  /// Channels with messages in the chunk; empty when the writer did not say.
  std::map<std::uint16_t, std::uint64_t> message_index_offsets;
};

Schema ParseSchema(std::string_view body);
Channel ParseChannel(std::string_view body);
Message ParseMessage(std::string_view body);
ChunkHeader ParseChunk(std::string_view body);
ChunkIndex ParseChunkIndex(std::string_view body);
/// Channel id -> message count, from a Statistics record.
std::map<std::uint16_t, std::uint64_t> ParseStatisticsCounts(std::string_view body);
/// Channel id and the log times of a Message Index record.
std::uint16_t ParseMessageIndex(std::string_view body,
                                std::int64_t& count,
                                std::int64_t& first_ns,
                                std::int64_t& last_ns);

/// CRC-32 (ISO-HDLC, as zlib's crc32), which MCAP uses for its checksums.
std::uint32_t Crc32(std::string_view data);

}  // namespace mpcal::bag::mcap
