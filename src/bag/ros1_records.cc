#include "bag/ros1_records.h"

#include "mpcal/bag.h"

namespace mpcal::bag::ros1 {
namespace {

std::string_view Need(const Fields& fields, std::string_view name, std::size_t size) {
  const auto it = fields.find(name);
  if (it == fields.end()) throw DataError("no '" + std::string(name) + "' field");
  if (size != 0 && it->second.size() != size) {
    throw DataError("field '" + std::string(name) + "' has " +
                    std::to_string(it->second.size()) + " bytes, not " +
                    std::to_string(size));
  }
  return it->second;
}

}  // namespace

Fields ParseFields(std::string_view header) {
  Fields fields;
  ByteCursor c(header);
  while (!c.empty()) {
    const std::string_view field =
        c.Bytes(c.U32("a header field's length"), "a header field");
    const std::size_t eq = field.find('=');
    if (eq == std::string_view::npos) throw DataError("a header field without '='");
    fields.insert_or_assign(std::string(field.substr(0, eq)),
                            std::string(field.substr(eq + 1)));
  }
  return fields;
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
  ByteCursor c(Need(fields, name, 8));
  const std::int64_t sec = c.U32("sec");
  return sec * 1'000'000'000 + c.U32("nsec");
}
std::string StringField(const Fields& fields, std::string_view name) {
  return std::string(Need(fields, name, 0));
}

Record RecordIn(std::string_view buffer, std::uint64_t offset) {
  ByteCursor c(buffer);
  c.Skip(offset, "the record start");
  Record r;
  r.fields = ParseFields(c.Bytes(c.U32("the header length"), "the record header"));
  r.op = OpOf(r.fields);
  r.data_length = c.U32("the data length");
  r.data_offset = c.offset();
  c.Skip(r.data_length, "the record data");
  r.next = c.offset();
  return r;
}

Record RecordAt(BagFile& file, std::uint64_t offset) {
  const std::string length = file.ReadAt(offset, 4, "the header length");
  const std::uint32_t header_length = ByteCursor(length).U32("the header length");
  if (header_length > kBagMaxFieldBytes) {
    throw DataError("a record header of " + std::to_string(header_length) +
                    " bytes is above the cap of " + std::to_string(kBagMaxFieldBytes));
  }
  const std::string header = file.ReadAt(offset + 4, header_length, "the record header");
  Record r;
  r.fields = ParseFields(header);
  r.op = OpOf(r.fields);
  const std::uint64_t data_at = offset + 4 + header_length;
  const std::string data_length = file.ReadAt(data_at, 4, "the data length");
  r.data_length = ByteCursor(data_length).U32("data length");
  r.data_offset = data_at + 4;
  if (r.data_length > file.size() - r.data_offset) {
    throw DataError("the record data needs " + std::to_string(r.data_length) +
                    " bytes but the file has " +
                    std::to_string(file.size() - r.data_offset) + " left");
  }
  r.next = r.data_offset + r.data_length;
  return r;
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
