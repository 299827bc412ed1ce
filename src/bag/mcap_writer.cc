// An MCAP file copied with its IMU messages edited, written as the MCAP
// specification lays one out (foxglove/mcap website/docs/spec/index.md, the
// sections cited in mcap_records.h, and Data End, Summary Offset and the
// summary section's grouping by opcode): the magic; a Header with the
// input's profile; the data section's records in the input's order, each
// Schema, Channel, Attachment and Metadata record byte for byte, each chunk
// with its own compression and a CRC-32 of what it unpacks to, followed by
// one Message Index per channel in it; Data End (no CRC of the data section:
// 0, which the specification allows); the summary (every Schema and Channel,
// a Statistics record, one Chunk Index per chunk), its Summary Offset
// records, the Footer with the summary's CRC-32, and the magic. The input's
// indexes and summary are not copied: they are made for the file written.
#include <algorithm>
#include <map>
#include <set>
#include <string>

#include "bag/bag_io.h"
#include "bag/bag_write.h"
#include "bag/decompress.h"
#include "bag/imu_decode.h"
#include "bag/mcap_records.h"
#include "bag/ros1_bag.h"
#include "mpcal/error.h"

namespace mpcal::bag {
namespace {

using namespace mcap;  // NOLINT(google-build-using-namespace): the records' names

constexpr std::uint8_t kAttachment = 0x09;
constexpr std::uint8_t kMetadata = 0x0C;
constexpr std::uint8_t kSummaryOffset = 0x0E;
// Message: channel_id (2), sequence (4), log_time (8), publish_time (8).
constexpr std::size_t kMessageDataAt = 2 + 4 + 8 + 8;
constexpr std::uint64_t kTailBytes = 1 + 8 + 20 + 8;  // Footer and magic

std::string McapRecord(std::uint8_t op, std::string_view body) {
  std::string out(1, static_cast<char>(op));
  Put(out, static_cast<std::uint64_t>(body.size()));
  out.append(body);
  return out;
}
void PutString(std::string& out, std::string_view s) {
  Put(out, static_cast<std::uint32_t>(s.size()));
  out.append(s);
}

struct IndexEntry {
  std::uint64_t log_time;
  std::uint64_t offset;
};

class McapRewriter {
 public:
  McapRewriter(BagFile& file,
               std::ostream& out,
               const std::string& topic,
               const ImuEdit& edit,
               const ImuCovariances& covariances)
      : file_(file), out_(out), topic_(topic), edit_(edit), covariances_(covariances) {}

  CountingOut& out() { return out_; }
  BagRewriteResult& result() { return result_; }
  bool topic_found() const { return !imu_.empty(); }
  const std::vector<BagTopic>& topics() const { return topics_; }
  const std::set<std::string>& compressions() const { return compressions_; }

  // The specification (spec/index.md, Schema and Channel) asks that the
  // records of one id be identical and come before what refers to them. The
  // copy's summary lists each id once, and a reader that takes the channels
  // from there would read a message the walk copied unedited, before the
  // channel's record said its topic, as an IMU message (or, for an id given
  // twice, as the other topic's): such a file is refused, not copied.
  void Schema(std::string_view raw, std::string_view body) {
    const mcap::Schema s = ParseSchema(body);
    schema_names_.try_emplace(s.id, s.name);
    const auto [first, fresh] = schemas_.try_emplace(s.id, raw);
    if (!fresh && first->second != raw) {
      throw DataError("schema " + std::to_string(s.id) +
                      " is given twice, by records that differ");
    }
  }

  void Channel(std::string_view raw, std::string_view body) {
    const mcap::Channel c = ParseChannel(body);
    const auto known = channels_.find(c.id);
    if (known != channels_.end() && known->second != raw) {
      throw DataError("channel " + std::to_string(c.id) +
                      " is given twice, by records that differ");
    }
    if (c.topic == topic_ && undefined_.count(c.id) != 0) {
      throw DataError("a message of channel " + std::to_string(c.id) +
                      " comes before the channel's record (topic '" + c.topic +
                      "'), which the MCAP specification puts first");
    }
    const auto schema = schema_names_.find(c.schema_id);
    const std::string type =
        schema != schema_names_.end() ? schema->second : std::string("(no schema)");
    if (c.topic == topic_) {
      const bool cdr = c.message_encoding == "cdr" && type == kRos2ImuType;
      if (!cdr && !(c.message_encoding == "ros1" && type == kRos1ImuType)) {
        throw Error(ErrorKind::kInput,
                    file_.path() + ": topic '" + c.topic + "' holds " + type +
                        " in encoding '" + c.message_encoding +
                        "', not sensor_msgs/msg/Imu in 'cdr' or sensor_msgs/Imu in "
                        "'ros1'");
      }
      imu_[c.id] = cdr;
    }
    if (channels_.try_emplace(c.id, raw).second) {
      topics_.push_back({c.topic, type, c.message_encoding, 0, 0, 0});
    }
  }

  // A Message record's body, its data edited when it is on the topic.
  // GCC 12 at -O3 takes the maps' and the set's keys, references to a field of
  // `m`, for pointers that outlive it (-Wdangling-pointer); nothing is kept.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wdangling-pointer"
#endif
  void Message(std::string& body) {
    const mcap::Message m = ParseMessage(body);
    ++channel_counts_[m.channel_id];
    start_ns_ = result_.imu_messages + result_.other_messages == 0
                    ? m.log_time_ns
                    : std::min(start_ns_, m.log_time_ns);
    end_ns_ = std::max(end_ns_, m.log_time_ns);
    const auto imu = imu_.find(m.channel_id);
    if (imu == imu_.end()) {
      if (channels_.count(m.channel_id) == 0) undefined_.insert(m.channel_id);
      ++result_.other_messages;
      return;
    }
    std::string data(m.data);
    EditImu(
        data, imu->second, static_cast<std::int64_t>(m.log_time_ns), edit_, covariances_);
    body.replace(kMessageDataAt, data.size(), data);
    ++result_.imu_messages;
  }
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

  void Chunk(const RecordSpan& r) {
    if (r.body_length > kBagMaxChunkBytes) throw DataError("a chunk above the size cap");
    const std::string packed = file_.ReadAt(r.body_offset, r.body_length, "the chunk");
    const ChunkHeader h = ParseChunk(packed);
    if (!IsKnownCompression(h.compression) || h.compression == "bz2" ||
        h.compression == "none") {
      throw DataError("unknown chunk compression '" + h.compression +
                      "' (an MCAP chunk has none, lz4 or zstd)");
    }
    std::string records = Decompress(h.compression, h.records, h.uncompressed_size);
    if (h.uncompressed_crc != 0 && Crc32(records) != h.uncompressed_crc) {
      throw DataError("the CRC-32 of the unpacked records does not match the chunk's");
    }
    std::map<std::uint16_t, std::vector<IndexEntry>> index;
    std::uint64_t start = 0, end = 0;
    for (std::uint64_t at = 0; at < records.size();) {
      const RecordSpan s = RecordIn(records, at);
      const std::string_view raw = std::string_view(records).substr(at, s.next - at);
      const std::string_view body = raw.substr(s.body_offset - at);
      if (s.op == kSchema) Schema(raw, body);
      if (s.op == kChannel) Channel(raw, body);
      if (s.op == kMessage) {
        std::string edited(body);
        Message(edited);
        const mcap::Message m = ParseMessage(edited);
        start = index.empty() ? m.log_time_ns : std::min(start, m.log_time_ns);
        end = index.empty() ? m.log_time_ns : std::max(end, m.log_time_ns);
        index[m.channel_id].push_back({m.log_time_ns, at});
        records.replace(s.body_offset, s.body_length, edited);
      }
      at = s.next;
    }
    compressions_.insert(h.compression.empty() ? "none" : h.compression);
    const std::string packed_records = Compress(h.compression, records);
    std::string chunk;
    Put(chunk, start), Put(chunk, end);
    Put(chunk, static_cast<std::uint64_t>(records.size()));
    Put(chunk, Crc32(records));
    PutString(chunk, h.compression);
    Put(chunk, static_cast<std::uint64_t>(packed_records.size()));
    chunk += packed_records;
    const std::uint64_t chunk_at = out_.pos();
    out_.Write(McapRecord(kChunk, chunk));
    const std::uint64_t chunk_length = out_.pos() - chunk_at;
    std::string offsets;
    for (const auto& [channel, entries] : index) {
      Put(offsets, channel), Put(offsets, out_.pos());
      std::string body;
      Put(body, channel);
      Put(body, static_cast<std::uint32_t>(16 * entries.size()));
      for (const IndexEntry& e : entries) Put(body, e.log_time), Put(body, e.offset);
      out_.Write(McapRecord(kMessageIndex, body));
    }
    std::string ci;
    Put(ci, start), Put(ci, end), Put(ci, chunk_at), Put(ci, chunk_length);
    PutString(ci, offsets);
    Put(ci, out_.pos() - chunk_at - chunk_length);
    PutString(ci, h.compression);
    Put(ci, static_cast<std::uint64_t>(packed_records.size()));
    Put(ci, static_cast<std::uint64_t>(records.size()));
    chunk_indexes_ += McapRecord(kChunkIndex, ci);
    ++chunk_count_;
  }

  void Count(std::uint8_t op) {
    if (op == kAttachment) ++attachments_;
    if (op == kMetadata) ++metadata_;
  }

  // Data End, the summary, its offsets, the footer and the magic.
  void Finish() {
    out_.Write(McapRecord(kDataEnd, std::string(4, '\0')));
    const std::uint64_t summary_at = out_.pos();
    std::string summary;
    std::string offsets;
    const auto group = [&](std::uint8_t op, const std::string& records) {
      if (records.empty()) return;
      std::string body(1, static_cast<char>(op));
      Put(body, summary_at + summary.size());
      Put(body, static_cast<std::uint64_t>(records.size()));
      offsets += McapRecord(kSummaryOffset, body);
      summary += records;
    };
    std::string schemas, channels;
    for (const auto& [id, raw] : schemas_) schemas += raw;
    for (const auto& [id, raw] : channels_) channels += raw;
    group(kSchema, schemas);
    group(kChannel, channels);
    group(kStatistics, McapRecord(kStatistics, Statistics()));
    group(kChunkIndex, chunk_indexes_);
    std::string tail = offsets;
    tail += static_cast<char>(kFooter);
    Put(tail, std::uint64_t{20});
    Put(tail, summary_at);
    Put(tail, summary_at + summary.size());
    const std::uint32_t crc = Crc32(summary + tail);
    Put(tail, crc);
    tail.append(kMagic);
    out_.Write(summary);
    out_.Write(tail);
  }

 private:
  std::string Statistics() const {
    std::string s;
    Put(s, static_cast<std::uint64_t>(result_.imu_messages + result_.other_messages));
    Put(s, static_cast<std::uint16_t>(schemas_.size()));
    Put(s, static_cast<std::uint32_t>(channels_.size()));
    Put(s, attachments_), Put(s, metadata_), Put(s, chunk_count_);
    Put(s, start_ns_), Put(s, end_ns_);
    std::string counts;
    for (const auto& [id, n] : channel_counts_) Put(counts, id), Put(counts, n);
    PutString(s, counts);
    return s;
  }

  BagFile& file_;
  CountingOut out_;
  const std::string& topic_;
  const ImuEdit& edit_;
  const ImuCovariances& covariances_;
  std::map<std::uint16_t, std::string> schema_names_;
  std::map<std::uint16_t, std::string> schemas_;   // id -> the record's bytes
  std::map<std::uint16_t, std::string> channels_;  // id -> the record's bytes
  std::vector<BagTopic> topics_;
  std::map<std::uint16_t, bool> imu_;  // channel id -> CDR (else ROS 1)
  std::set<std::uint16_t> undefined_;  // ids with a message before any record
  std::map<std::uint16_t, std::uint64_t> channel_counts_;
  std::string chunk_indexes_;
  std::uint64_t start_ns_ = 0, end_ns_ = 0;
  std::uint32_t attachments_ = 0, metadata_ = 0, chunk_count_ = 0;
  BagRewriteResult result_;
  std::set<std::string> compressions_;
};

std::string At(std::uint64_t offset) { return "byte " + std::to_string(offset); }

// Where the data section ends: the summary's start or the footer's, or the
// file's end for a file without a footer.
std::uint64_t DataEnd(BagFile& file, std::vector<std::string>& warnings) {
  if (file.size() >= kMagic.size() + kTailBytes) {
    const std::uint64_t footer_at = file.size() - kTailBytes;
    const std::string footer = file.ReadAt(footer_at, kTailBytes, "the footer");
    ByteCursor c(footer);
    const bool is_footer = c.U8("op") == kFooter && c.U64("length") == 20;
    const std::uint64_t summary_start = c.U64("summary_start");
    c.Skip(8 + 4, "the footer");
    if (is_footer && c.Bytes(kMagic.size(), "magic") == kMagic) {
      return summary_start >= kMagic.size() && summary_start < footer_at ? summary_start
                                                                         : footer_at;
    }
  }
  warnings.push_back(file.path() +
                     ": the file has no footer (it is cut short or was not closed); the "
                     "records it holds are copied and the file written is closed");
  return file.size();
}

}  // namespace

BagRewriteResult RewriteMcap(const std::string& input,
                             std::ostream& output,
                             const std::string& topic,
                             const ImuEdit& edit,
                             const ImuCovariances& covariances,
                             std::vector<std::string>& warnings) {
  BagFile file(input);
  if (file.ReadSome(0, kMagic.size()) != kMagic) {
    ThrowBagError(input, "not an MCAP file (it does not start with the MCAP magic)");
  }
  const std::uint64_t data_end = DataEnd(file, warnings);
  const bool complete = data_end != file.size();
  McapRewriter w(file, output, topic, edit, covariances);
  w.out().Write(kMagic);
  std::uint64_t offset = kMagic.size();
  try {
    const RecordSpan h = RecordAt(file, offset);
    if (h.op != kHeader || h.body_length > kBagMaxFieldBytes)
      throw DataError("the first record is not a header");
    const std::string body = file.ReadAt(h.body_offset, h.body_length, "the header");
    ByteCursor c(body);
    std::string header;
    PutString(header, String(c, "the profile"));
    PutString(header, "mpcal");
    w.out().Write(McapRecord(kHeader, header));
    offset = h.next;
  } catch (const DataError& e) {
    ThrowBagError(input, "header at " + At(offset) + ": " + e.what());
  }
  while (offset < data_end) {
    RecordSpan r;
    try {
      r = RecordAt(file, offset);
      if (r.next > data_end) throw DataError("the record runs past the data section");
    } catch (const DataError& e) {
      if (complete) ThrowBagError(input, "record at " + At(offset) + ": " + e.what());
      warnings.push_back(input + ": the file is cut short at " + At(offset) + " (" +
                         e.what() + "); the messages before it are copied");
      break;
    }
    if (r.op == kDataEnd || r.op == kFooter) break;
    try {
      if (r.op == kChunk) {
        w.Chunk(r);
      } else if (r.op == kMessageIndex || r.op == kChunkIndex || r.op == kStatistics ||
                 r.op == kSummaryOffset || r.op == 0x0A || r.op == 0x0D) {
        // Indexes, made afresh for the file written.
      } else {
        if (r.body_length > kBagMaxRecordBytes)
          throw DataError("a record above the size cap");
        std::string raw = file.ReadAt(offset, r.next - offset, "the record");
        const std::string_view body = std::string_view(raw).substr(9);
        if (r.op == kSchema) w.Schema(raw, body);
        if (r.op == kChannel) w.Channel(raw, body);
        if (r.op == kMessage) {
          std::string edited(body);
          w.Message(edited);
          raw = McapRecord(kMessage, edited);
        }
        w.Count(r.op);
        w.out().Write(raw);
      }
    } catch (const DataError& e) {
      ThrowBagError(
          input,
          (r.op == kChunk ? "chunk at " : "record at ") + At(offset) + ": " + e.what());
    }
    offset = r.next;
  }
  if (!w.topic_found()) {
    throw Error(
        ErrorKind::kInput,
        input + ": no topic '" + topic + "'; the file holds " + ListTopics(w.topics()));
  }
  w.Finish();
  BagRewriteResult result = w.result();
  result.format = BagFormat::kMcap;
  result.compressions.assign(w.compressions().begin(), w.compressions().end());
  return result;
}

}  // namespace mpcal::bag
