// A ROS 1 record header's fields, read in place. The header bytes are built
// here as rosbag's writer lays them out (bag.py 2013-2052 in Debian's
// python3-rosbag: a u32 length, then "name=value", for each field).
#include "bag/ros1_records.h"

#include <cstdint>
#include <string>

#include <gtest/gtest.h>

namespace mpcal::bag::ros1 {
namespace {

std::string U32(std::uint32_t v) {
  std::string out(4, '\0');
  for (int i = 0; i < 4; ++i) out[i] = static_cast<char>((v >> (8 * i)) & 0xff);
  return out;
}

std::string Field(const std::string& name, const std::string& value) {
  const std::string field = name + "=" + value;
  return U32(static_cast<std::uint32_t>(field.size())) + field;
}

// A message data record's header: op, conn, time (sec, nsec).
std::string MessageHeader(std::uint32_t conn, std::uint32_t sec, std::uint32_t nsec) {
  return Field("op", std::string(1, '\x02')) + Field("conn", U32(conn)) +
         Field("time", U32(sec) + U32(nsec));
}

TEST(Ros1Fields, MessageHeaderFieldsAreReadInPlace) {
  const std::string header = MessageHeader(7, 1700000000, 123456789);
  const Fields fields = Fields::Viewing(header);
  EXPECT_EQ(OpOf(fields), kMessageData);
  EXPECT_EQ(U32Field(fields, "conn"), 7u);
  EXPECT_EQ(TimeField(fields, "time"), 1700000000LL * 1'000'000'000LL + 123456789);
  EXPECT_EQ(fields.count("topic"), 0u);
  // The values view the header's bytes.
  EXPECT_EQ(fields.Find("conn")->data(), header.data() + header.find("conn=") + 5);
}

TEST(Ros1Fields, ANameIsMatchedWholeAndTheLastOfARepeatedOneCounts) {
  const std::string header = Field("connection", U32(1)) + Field("con", U32(2)) +
                             Field("conn", U32(3)) + Field("conn", U32(4)) +
                             Field("op", std::string(1, '\x02'));
  const Fields fields = ParseFields(header);
  EXPECT_EQ(U32Field(fields, "conn"), 4u);
  EXPECT_EQ(U32Field(fields, "con"), 2u);
  EXPECT_EQ(U32Field(fields, "connection"), 1u);
  EXPECT_EQ(fields.count("co"), 0u);
  // A value may hold '=' itself: the name ends at the first one.
  const Fields eq = ParseFields(Field("topic", "/a=b"));
  EXPECT_EQ(StringField(eq, "topic"), "/a=b");
}

TEST(Ros1Fields, OwnedFieldsOutliveTheirSourceAndSurviveCopies) {
  Fields copy;
  {
    std::string header = Field("topic", "/imu") + Field("op", std::string(1, '\x07'));
    const Fields owned = ParseFields(header);
    header.assign(header.size(), 'x');
    copy = owned;
  }
  EXPECT_EQ(StringField(copy, "topic"), "/imu");
  EXPECT_EQ(OpOf(copy), kConnection);
}

TEST(Ros1Fields, DamagedHeadersAreRefused) {
  EXPECT_THROW(Fields::Viewing(U32(5) + "op"), DataError);    // length past the end
  EXPECT_THROW(Fields::Viewing(U32(4) + "op02"), DataError);  // no '='
  EXPECT_THROW(Fields::Viewing(std::string_view("\x01", 1)), DataError);  // a cut length
  const std::string two = Field("op", "\x02\x02");
  const Fields fields = Fields::Viewing(two);
  EXPECT_THROW(OpOf(fields), DataError);              // op of two bytes
  EXPECT_THROW(U32Field(fields, "conn"), DataError);  // missing
  EXPECT_NO_THROW(Fields::Viewing(""));
}

// A record in a chunk: its fields view the chunk's bytes, and its data
// follows the header.
TEST(Ros1Fields, RecordInAChunkPointsAtItsData) {
  const std::string header = MessageHeader(3, 10, 20);
  const std::string chunk =
      U32(static_cast<std::uint32_t>(header.size())) + header + U32(5) + "hello" + "rest";
  const Record r = RecordIn(chunk, 0);
  EXPECT_EQ(r.op, kMessageData);
  EXPECT_EQ(U32Field(r.fields, "conn"), 3u);
  EXPECT_EQ(TimeField(r.fields, "time"), 10'000'000'020LL);
  EXPECT_EQ(chunk.substr(r.data_offset, r.data_length), "hello");
  EXPECT_EQ(r.next, chunk.size() - 4);
  EXPECT_THROW(RecordIn(chunk.substr(0, chunk.size() - 6), 0), DataError);
}

}  // namespace
}  // namespace mpcal::bag::ros1
