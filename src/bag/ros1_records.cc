#include "bag/ros1_records.h"

#include <cstring>

#include "mpcal/bag.h"

namespace mpcal::bag::ros1 {
namespace {

std::string_view Need(std::optional<std::string_view> value,
                      std::string_view name,
                      std::size_t size) {
  if (!value) throw DataError("no '" + std::string(name) + "' field");
  if (size != 0 && value->size() != size) {
    throw DataError("field '" + std::string(name) + "' has " +
                    std::to_string(value->size()) + " bytes, not " +
                    std::to_string(size));
  }
  return *value;
}

// Whether `field` starts with `name`: a loop rather than memcmp, which for
// names of two to nine bytes costs more in the call than in the comparison.
bool SameName(std::string_view field, std::string_view name) {
  for (std::size_t i = 0; i < name.size(); ++i) {
    if (field[i] != name[i]) return false;
  }
  return true;
}

std::string_view Need(const Fields& fields, std::string_view name, std::size_t size) {
  return Need(fields.Find(name), name, size);
}

std::int64_t TimeOf(std::string_view value) {
  ByteCursor c(value);
  const std::int64_t sec = c.U32("sec");
  return sec * 1'000'000'000 + c.U32("nsec");
}

// A record's op, and a message record's conn and time, from the fields the
// check noted: read for every message, so without looking a name up.
void ReadNotedFields(Record& r) {
  r.op = ByteCursor(Need(r.fields.Op(), "op", 1)).U8("op");
  if (r.op != kMessageData) return;
  r.conn = ByteCursor(Need(r.fields.Conn(), "conn", 4)).U32("a u32 field");
  r.time_ns = TimeOf(Need(r.fields.Time(), "time", 8));
}

}  // namespace

void Fields::Check() {
  const std::string_view header = bytes();
  ByteCursor c(header);
  while (!c.empty()) {
    const std::string_view field =
        c.Bytes(c.U32("a header field's length"), "a header field");
    // The name is a few bytes: a loop finds its end sooner than memchr's call.
    std::size_t eq = 0;
    while (eq < field.size() && field[eq] != '=') ++eq;
    if (eq == field.size()) throw DataError("a header field without '='");
    Noted* noted = nullptr;
    if (eq == 2 && SameName(field, "op")) {
      noted = &op_;
    } else if (eq == 4 && SameName(field, "conn")) {
      noted = &conn_;
    } else if (eq == 4 && SameName(field, "time")) {
      noted = &time_;
    }
    if (noted != nullptr) {
      // The value follows the '='; the last of a repeated name counts.
      noted->pos = static_cast<std::size_t>(field.data() - header.data()) + eq + 1;
      noted->size = field.size() - eq - 1;
      noted->found = true;
    }
  }
}

const Fields::Noted* Fields::NotedFor(std::string_view name) const {
  if (name.size() == 2 && SameName(name, "op")) return &op_;
  if (name.size() == 4 && SameName(name, "conn")) return &conn_;
  if (name.size() == 4 && SameName(name, "time")) return &time_;
  return nullptr;
}

Fields Fields::Viewing(std::string_view header) {
  Fields fields;
  fields.view_ = header;
  fields.Check();
  return fields;
}

Fields Fields::Owning(std::string header) {
  Fields fields;
  fields.owned_ = std::move(header);
  fields.owning_ = true;
  fields.Check();
  return fields;
}

std::optional<std::string_view> Fields::Find(std::string_view name) const {
  // The header was checked when the fields were made: every length fits and
  // every field has an '='.
  const std::string_view header = bytes();
  if (const Noted* noted = NotedFor(name)) {
    if (!noted->found) return std::nullopt;
    return header.substr(noted->pos, noted->size);
  }
  std::optional<std::string_view> found;
  std::size_t pos = 0;
  while (pos < header.size()) {
    std::uint32_t length = 0;
    std::memcpy(&length, header.data() + pos, sizeof length);
    const std::string_view field = header.substr(pos + sizeof length, length);
    pos += sizeof length + length;
    if (field.size() > name.size() && field[name.size()] == '=' &&
        SameName(field, name)) {
      found = field.substr(name.size() + 1);
    }
  }
  return found;
}

Fields ParseFields(std::string_view header) {
  return Fields::Owning(std::string(header));
}

std::uint8_t OpOf(const Fields& fields) {
  return ByteCursor(Need(fields, "op", 1)).U8("op");
}
std::uint32_t U32Field(const Fields& fields, std::string_view name) {
  return ByteCursor(Need(fields, name, 4)).U32("a u32 field");
}
std::uint64_t U64Field(const Fields& fields, std::string_view name) {
  return ByteCursor(Need(fields, name, 8)).U64("a u64 field");
}
std::int64_t TimeField(const Fields& fields, std::string_view name) {
  return TimeOf(Need(fields, name, 8));
}
std::string StringField(const Fields& fields, std::string_view name) {
  return std::string(Need(fields, name, 0));
}

Record RecordIn(std::string_view buffer, std::uint64_t offset) {
  ByteCursor c(buffer);
  c.Skip(offset, "the record start");
  Record r;
  r.fields = Fields::Viewing(c.Bytes(c.U32("the header length"), "the record header"));
  ReadNotedFields(r);
  r.data_length = c.U32("the data length");
  r.data_offset = c.offset();
  c.Skip(r.data_length, "the record data");
  r.next = c.offset();
  return r;
}

Record RecordAt(BagFile& file, std::uint64_t offset) {
  // One read covers the lengths and the header of a usual record; a longer
  // header (a connection's) is read on its own.
  constexpr std::uint64_t kFirstReadBytes = 512;
  const std::string first = file.ReadSome(offset, kFirstReadBytes);
  std::uint32_t header_length = 0;
  if (first.size() >= 4) {
    header_length = ByteCursor(first).U32("the header length");
  } else {
    const std::string length = file.ReadAt(offset, 4, "the header length");
    header_length = ByteCursor(length).U32("the header length");
  }
  if (header_length > kBagMaxFieldBytes) {
    throw DataError("a record header of " + std::to_string(header_length) +
                    " bytes is above the cap of " + std::to_string(kBagMaxFieldBytes));
  }
  Record r;
  const std::uint64_t data_at = offset + 4 + header_length;
  std::uint32_t data_length = 0;
  if (first.size() >= 4 + std::uint64_t{header_length} + 4) {
    ByteCursor c(first);
    c.Skip(4, "the header length");
    r.fields = ParseFields(c.Bytes(header_length, "the record header"));
    data_length = c.U32("the data length");
  } else {
    r.fields =
        Fields::Owning(file.ReadAt(offset + 4, header_length, "the record header"));
    const std::string length = file.ReadAt(data_at, 4, "the data length");
    data_length = ByteCursor(length).U32("data length");
  }
  ReadNotedFields(r);
  r.data_length = data_length;
  r.data_offset = data_at + 4;
  if (r.data_length > file.size() - r.data_offset) {
    throw DataError("the record data needs " + std::to_string(r.data_length) +
                    " bytes but the file has " +
                    std::to_string(file.size() - r.data_offset) + " left");
  }
  r.next = r.data_offset + r.data_length;
  return r;
}

std::vector<IndexDataEntry> ParseIndexData(std::string_view data, std::uint32_t count) {
  // Checked before the room is made: the count is read from the file.
  if (std::uint64_t{count} * 12 > data.size()) {
    throw DataError("an index data record of " + std::to_string(count) +
                    " entries holds " + std::to_string(data.size()) + " bytes");
  }
  ByteCursor c(data);
  std::vector<IndexDataEntry> entries(count);
  for (IndexDataEntry& e : entries) {
    e.time_ns = TimeOf(c.Bytes(8, "an index entry"));
    e.offset = c.U32("an index entry");
  }
  return entries;
}

Connection ParseConnection(const Record& record, std::string_view data) {
  Connection c;
  c.id = U32Field(record.fields, "conn");
  c.topic = StringField(record.fields, "topic");
  const Fields header = ParseFields(data);
  c.type = StringField(header, "type");
  c.md5sum = StringField(header, "md5sum");
  return c;
}

}  // namespace mpcal::bag::ros1
