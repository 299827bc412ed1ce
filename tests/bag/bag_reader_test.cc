// The bag readers against files written by other tools (tests/data/bags/:
// Debian's rosbag, Foxglove's @mcap/core, Python's sqlite3 with a CDR encoder
// of its own), each made from session.csv: every message must equal its CSV
// row exactly (the doubles are stored as doubles).
#include "mpcal/bag.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "bag_fixture.h"
#include "mpcal/error.h"
#include "test_util.h"

namespace mpcal {
namespace {

using ::testing::HasSubstr;
using testing::ReadFile;
using testing::ScratchDir;

constexpr std::int64_t kEpochNs = 1700000000LL * 1000000000LL;
constexpr std::int64_t kLatencyNs = 2'000'000;
constexpr std::size_t kRows = 380;
constexpr std::size_t kChatterMessages = 338;  // 300 first, then one per ten rows

using testing::Bag;

struct Row {
  std::int64_t stamp_ns = 0;
  std::int64_t receive_ns = 0;
  Eigen::Vector3d accel, gyro;
};

// session.csv as the fixture scripts turn it into messages.
std::vector<Row> SessionRows() {
  std::ifstream in(Bag("session.csv"));
  std::string line;
  std::getline(in, line);  // header
  std::vector<Row> rows;
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string cell;
    std::vector<double> v;
    while (std::getline(ss, cell, ',')) v.push_back(std::strtod(cell.c_str(), nullptr));
    Row r;
    const std::int64_t t_ns = std::llround(v.at(0) * 1e9);
    r.stamp_ns = kEpochNs + t_ns;
    r.receive_ns = kEpochNs + t_ns + kLatencyNs;
    r.accel = {v.at(1), v.at(2), v.at(3)};
    r.gyro = {v.at(4), v.at(5), v.at(6)};
    rows.push_back(r);
  }
  std::swap(rows.at(100).stamp_ns, rows.at(101).stamp_ns);  // written out of order
  return rows;
}

std::vector<ImuMessage> ReadAll(const std::string& path,
                                std::vector<std::string>& warnings,
                                const std::string& topic = "/imu/data") {
  std::vector<ImuMessage> all;
  ReadImuMessages(
      path,
      topic,
      [&](std::span<const ImuMessage> batch) {
        all.insert(all.end(), batch.begin(), batch.end());
      },
      warnings);
  return all;
}

// The first messages.size() rows, exactly.
void ExpectSessionPrefix(const std::vector<ImuMessage>& messages) {
  const std::vector<Row> rows = SessionRows();
  ASSERT_LE(messages.size(), rows.size());
  for (std::size_t i = 0; i < messages.size(); ++i) {
    SCOPED_TRACE("message " + std::to_string(i));
    EXPECT_EQ(messages[i].stamp_ns, rows[i].stamp_ns);
    EXPECT_EQ(messages[i].receive_ns, rows[i].receive_ns);
    EXPECT_EQ(messages[i].linear_acceleration_mps2, rows[i].accel);
    EXPECT_EQ(messages[i].angular_velocity_radps, rows[i].gyro);
    if (::testing::Test::HasFailure()) return;
  }
}

std::string ErrorText(const std::function<void()>& f) {
  try {
    f();
  } catch (const mpcal::Error& e) {
    return e.what();
  }
  return "no error";
}

std::size_t FindNth(const std::string& s, const std::string& needle, int n) {
  std::size_t at = std::string::npos;
  for (int k = 0; k <= n; ++k) at = s.find(needle, at == std::string::npos ? 0 : at + 1);
  return at;
}

class EveryFormat : public ::testing::TestWithParam<const char*> {};

TEST_P(EveryFormat, GivesEverySessionRowExactlyInFileOrder) {
  std::vector<std::string> warnings;
  const std::vector<ImuMessage> messages = ReadAll(Bag(GetParam()), warnings);
  ASSERT_EQ(messages.size(), kRows);
  ExpectSessionPrefix(messages);
  EXPECT_THAT(warnings, ::testing::IsEmpty());
}

INSTANTIATE_TEST_SUITE_P(Fixtures,
                         EveryFormat,
                         ::testing::Values("imu_none.bag",
                                           "imu_among_images.bag",
                                           "imu_bz2.bag",
                                           "imu_lz4.bag",
                                           "imu_cdr_zstd.mcap",
                                           "imu_cdr_be_lz4.mcap",
                                           "imu_ros1.mcap",
                                           "imu_cdr_plain.mcap",
                                           "imu_chatter_first.mcap",
                                           "imu_ros2",
                                           "imu_ros2/imu_ros2_0.db3"));

TEST(DetectBagFormat, TellsTheFormatsApart) {
  EXPECT_EQ(DetectBagFormat(Bag("imu_lz4.bag")), BagFormat::kRos1);
  EXPECT_EQ(DetectBagFormat(Bag("imu_cdr_zstd.mcap")), BagFormat::kMcap);
  EXPECT_EQ(DetectBagFormat(Bag("imu_ros2")), BagFormat::kRos2Sqlite);
  EXPECT_THAT(ErrorText([] { DetectBagFormat(Bag("session.csv")); }),
              HasSubstr("starts with 't,ax,ay,az,gx,gy'"));
  ScratchDir dir;
  EXPECT_THAT(ErrorText([&] { DetectBagFormat(dir.Write("empty.bag", "")); }),
              HasSubstr("empty.bag: the file is empty"));
}

void ExpectTopics(const BagSummary& s,
                  const std::string& imu_type,
                  const std::string& string_type,
                  const std::string& encoding) {
  ASSERT_EQ(s.topics.size(), 2u);
  const std::vector<Row> rows = SessionRows();
  for (const BagTopic& t : s.topics) {
    EXPECT_EQ(t.encoding, encoding);
    if (t.name == "/imu/data") {
      EXPECT_EQ(t.type, imu_type);
      EXPECT_EQ(t.messages, static_cast<std::int64_t>(kRows));
      EXPECT_EQ(t.first_ns, rows.front().receive_ns);
      EXPECT_EQ(t.last_ns, rows.back().receive_ns);
    } else {
      EXPECT_EQ(t.name, "/chatter");
      EXPECT_EQ(t.type, string_type);
    }
  }
}

// rosbag2 also stores MCAP files in its directories.
TEST(ReadImuMessages, Ros2DirectoryOfMcapFiles) {
  ScratchDir dir;
  std::filesystem::create_directory(dir.path() / "bag");
  dir.Write("bag/bag_0.mcap", ReadFile(Bag("imu_cdr_be_lz4.mcap")));
  dir.Write("bag/metadata.yaml", "rosbag2_bagfile_information:\n");
  EXPECT_EQ(DetectBagFormat(dir.Path("bag")), BagFormat::kRos2Sqlite);
  std::vector<std::string> w;
  const auto messages = ReadAll(dir.Path("bag"), w);
  ASSERT_EQ(messages.size(), kRows);
  ExpectSessionPrefix(messages);
  ExpectTopics(
      InspectBag(dir.Path("bag")), "sensor_msgs/msg/Imu", "std_msgs/msg/String", "cdr");
}

TEST(InspectBag, Ros1TopicsCountsAndCompressionFromTheIndex) {
  const BagSummary s = InspectBag(Bag("imu_bz2.bag"));
  EXPECT_EQ(s.format, BagFormat::kRos1);
  ExpectTopics(s, "sensor_msgs/Imu", "std_msgs/String", "ros1");
  for (const BagTopic& t : s.topics) {
    if (t.name == "/chatter") {
      EXPECT_EQ(t.messages, static_cast<std::int64_t>(kChatterMessages));
    }
  }
  EXPECT_THAT(s.compressions, ::testing::ElementsAre("bz2"));
  EXPECT_THAT(s.warnings, ::testing::IsEmpty());
}

TEST(InspectBag, McapTopicsCountsAndCompression) {
  const BagSummary s = InspectBag(Bag("imu_cdr_zstd.mcap"));
  EXPECT_EQ(s.format, BagFormat::kMcap);
  ExpectTopics(s, "sensor_msgs/msg/Imu", "std_msgs/msg/String", "cdr");
  EXPECT_THAT(s.compressions, ::testing::ElementsAre("zstd"));
  const BagSummary plain = InspectBag(Bag("imu_cdr_plain.mcap"));
  ExpectTopics(plain, "sensor_msgs/msg/Imu", "std_msgs/msg/String", "cdr");
}

TEST(InspectBag, Ros2TopicsAndCounts) {
  const BagSummary s = InspectBag(Bag("imu_ros2"));
  EXPECT_EQ(s.format, BagFormat::kRos2Sqlite);
  ExpectTopics(s, "sensor_msgs/msg/Imu", "std_msgs/msg/String", "cdr");
}

// The topics alone: as InspectBag lists them, with the index's counts; a ROS
// 2 bag's SQLite file is not counted (its messages would be read for it).
TEST(ListBagTopics, TheIndexsCountsOrForASqliteBagNone) {
  for (const char* file : {"imu_bz2.bag", "imu_cdr_zstd.mcap"}) {
    const BagSummary s = InspectBag(Bag(file));
    const std::vector<BagTopic> listed = ListBagTopics(Bag(file));
    ASSERT_EQ(listed.size(), s.topics.size()) << file;
    for (std::size_t i = 0; i < listed.size(); ++i) {
      EXPECT_EQ(listed[i].name, s.topics[i].name) << file;
      EXPECT_EQ(listed[i].type, s.topics[i].type) << file;
      EXPECT_EQ(listed[i].messages, s.topics[i].messages) << file;
    }
  }
  BagSummary ros2;
  ros2.topics = ListBagTopics(Bag("imu_ros2"));
  ASSERT_EQ(ros2.topics.size(), 2u);
  for (const BagTopic& t : ros2.topics) {
    EXPECT_EQ(t.messages, 0) << t.name;
    EXPECT_EQ(t.first_ns, 0) << t.name;
    EXPECT_EQ(t.encoding, "cdr") << t.name;
  }
  const BagSummary counted = InspectBag(Bag("imu_ros2"));
  for (std::size_t i = 0; i < 2; ++i) {
    EXPECT_EQ(ros2.topics[i].name, counted.topics[i].name);
    EXPECT_EQ(ros2.topics[i].type, counted.topics[i].type);
  }
  // make_ros2_db3.py's /chatter: one message with every tenth row, at its
  // receive time (as SQLite's own COUNT, MIN and MAX over the table give them).
  for (const BagTopic& t : counted.topics) {
    if (t.name == "/chatter") {
      EXPECT_EQ(t.messages, static_cast<std::int64_t>(kRows / 10));
      EXPECT_EQ(t.first_ns, 1700000000002000000);
      EXPECT_EQ(t.last_ns, 1700000018502000000);
    }
  }
}

TEST(ReadImuMessages, RefusesATopicOfAnotherTypeByName) {
  std::vector<std::string> w;
  for (const char* file : {"imu_none.bag", "imu_cdr_zstd.mcap", "imu_ros2"}) {
    EXPECT_THAT(ErrorText([&] { ReadAll(Bag(file), w, "/chatter"); }),
                ::testing::AllOf(HasSubstr("'/chatter'"), HasSubstr("std_msgs/")))
        << file;
  }
}

TEST(ReadImuMessages, AnAbsentTopicListsTheTopicsThere) {
  std::vector<std::string> w;
  for (const char* file :
       {"imu_lz4.bag", "imu_ros1.mcap", "imu_ros2", "imu_cdr_plain.mcap"}) {
    EXPECT_THAT(ErrorText([&] { ReadAll(Bag(file), w, "/imu"); }),
                ::testing::AllOf(HasSubstr("no topic '/imu'"),
                                 HasSubstr("/imu/data (sensor_msgs/")))
        << file;
  }
}

TEST(ReadImuMessages, AnEmptyBagHasNoTopic) {
  std::vector<std::string> w;
  EXPECT_THAT(ErrorText([&] { ReadAll(Bag("empty.bag"), w); }),
              HasSubstr("empty.bag: no topic '/imu/data'; the bag holds none"));
}

TEST(ReadImuMessages, WrongMagicIsRefused) {
  ScratchDir dir;
  std::string bag = ReadFile(Bag("imu_none.bag"));
  bag[9] = '1';  // "#ROSBAG V1.0"
  std::vector<std::string> w;
  EXPECT_THAT(ErrorText([&] { ReadAll(dir.Write("old.bag", bag), w); }),
              HasSubstr("old.bag: a ROS 1 bag of format 1.0 (only 2.0 is read)"));
}

// A ROS 1 bag cut short has lost its index (written at the end): the chunks
// before the cut are read, with a warning.
TEST(ReadImuMessages, Ros1BagCutShortGivesWhatItHolds) {
  ScratchDir dir;
  const std::string bag = ReadFile(Bag("imu_lz4.bag"));
  std::vector<std::string> w;
  const auto messages = ReadAll(dir.Write("cut.bag", bag.substr(0, bag.size() / 2)), w);
  EXPECT_GT(messages.size(), 50u);
  EXPECT_LT(messages.size(), kRows);
  ExpectSessionPrefix(messages);
  EXPECT_THAT(w, ::testing::Contains(HasSubstr("the file is cut short at byte")));
}

TEST(ReadImuMessages, McapCutShortGivesWhatItHolds) {
  ScratchDir dir;
  const std::string mcap = ReadFile(Bag("imu_cdr_zstd.mcap"));
  std::vector<std::string> w;
  const auto messages =
      ReadAll(dir.Write("cut.mcap", mcap.substr(0, mcap.size() / 2)), w);
  EXPECT_GT(messages.size(), 50u);
  EXPECT_LT(messages.size(), kRows);
  ExpectSessionPrefix(messages);
  EXPECT_THAT(w, ::testing::Contains(HasSubstr("no footer")));
  EXPECT_THAT(w, ::testing::Contains(HasSubstr("the file is cut short at byte")));
}

TEST(ReadImuMessages, CorruptChunkNamesItsOffset) {
  ScratchDir dir;
  std::string bag = ReadFile(Bag("imu_bz2.bag"));
  const std::size_t chunk = FindNth(bag, "compression=bz2", 5);
  for (std::size_t i = chunk + 200; i < chunk + 260; ++i) bag[i] = '\x55';
  std::vector<std::string> w;
  EXPECT_THAT(ErrorText([&] { ReadAll(dir.Write("bad.bag", bag), w); }),
              ::testing::AllOf(HasSubstr("bad.bag: chunk at byte"), HasSubstr("bz2")));
}

TEST(ReadImuMessages, UnknownCompressionIsNamed) {
  ScratchDir dir;
  std::string bag = ReadFile(Bag("imu_bz2.bag"));
  for (std::size_t at = bag.find("compression=bz2"); at != std::string::npos;
       at = bag.find("compression=bz2", at + 1)) {
    bag.replace(at + 12, 3, "xz9");
  }
  std::vector<std::string> w;
  EXPECT_THAT(ErrorText([&] { ReadAll(dir.Write("xz.bag", bag), w); }),
              HasSubstr("unknown chunk compression 'xz9'"));
}

// The index says which chunks hold the topic: the first chunks hold only
// /chatter, so damage there does not stop the IMU messages being read.
TEST(ReadImuMessages, SkipsChunksWithoutTheTopic) {
  ScratchDir dir;
  std::string bag = ReadFile(Bag("imu_none.bag"));
  const std::size_t first_chunk = FindNth(bag, "compression=none", 0);
  for (std::size_t i = first_chunk + 100; i < first_chunk + 400; ++i) bag[i] = '\xff';
  std::vector<std::string> w;
  const auto messages = ReadAll(dir.Write("skip.bag", bag), w);
  EXPECT_EQ(messages.size(), kRows);
  // The same damage in a chunk that holds IMU messages is found.
  std::string imu = ReadFile(Bag("imu_none.bag"));
  const std::size_t later = FindNth(imu, "compression=none", 5);
  for (std::size_t i = later + 100; i < later + 400; ++i) imu[i] = '\xff';
  EXPECT_THAT(ErrorText([&] { ReadAll(dir.Write("bad.bag", imu), w); }),
              HasSubstr("chunk at byte"));
}

// A stored chunk whose IMU records are a small part of it (images between
// them) is read where the index data records after it put them: the image
// records are not read, so damage to every one of them leaves every row.
TEST(ReadImuMessages, ReadsAStoredChunkWhereItsIndexPutsTheTopic) {
  ScratchDir dir;
  std::string bag = ReadFile(Bag("imu_among_images.bag"));
  const std::string image_record("\x04\0\0\0op=\x02\x09\0\0\0conn=\0\0\0\0", 21);
  int damaged = 0;
  for (std::size_t at = bag.find(image_record); at != std::string::npos;
       at = bag.find(image_record, at + 1), ++damaged) {
    bag.replace(at - 4, 4, "\xff\xff\xff\x7f");  // the record header's length
  }
  ASSERT_EQ(damaged, 19);
  std::vector<std::string> w;
  const auto messages = ReadAll(dir.Write("images.bag", bag), w);
  ASSERT_EQ(messages.size(), kRows);
  ExpectSessionPrefix(messages);
  EXPECT_THAT(w, ::testing::IsEmpty());
}

// An index entry is checked against the record at its offset: one whose time
// is not the record's is refused, naming the chunk.
TEST(ReadImuMessages, AnIndexEntryThatIsNotItsRecordIsRefused) {
  ScratchDir dir;
  std::string bag = ReadFile(Bag("imu_among_images.bag"));
  const std::string imu_index("\x04\0\0\0op=\x04\x09\0\0\0conn=\x01\0\0\0", 21);
  const std::size_t index = FindNth(bag, imu_index, 3);
  ASSERT_NE(index, std::string::npos);
  // After the count field: the data's length, then the first entry's sec
  // and nsec.
  const std::size_t entry = bag.find("count=", index) + 6 + 4 + 4;
  bag[entry + 4] = static_cast<char>(bag[entry + 4] + 1);
  std::vector<std::string> w;
  EXPECT_THAT(ErrorText([&] { ReadAll(dir.Write("index.bag", bag), w); }),
              ::testing::AllOf(HasSubstr("index.bag: chunk at byte"),
                               HasSubstr("the index gives a message of connection 1"),
                               HasSubstr("the record there is not it")));
}

// The summary's chunk indexes say which chunks hold the topic: the first
// chunks of imu_chatter_first.mcap hold only /chatter, so damage to their
// compressed bytes does not stop the IMU messages being read, nor the
// inspection, which counts from the message indexes.
TEST(ReadImuMessages, McapSkipsChunksWithoutTheTopic) {
  ScratchDir dir;
  const std::string zstd("\x04\0\0\0zstd", 8);  // a chunk's compression field
  std::string mcap = ReadFile(Bag("imu_chatter_first.mcap"));
  const std::size_t first_chunk = FindNth(mcap, zstd, 0);
  ASSERT_NE(first_chunk, std::string::npos);
  // After the name: the records' length (8 bytes), then the zstd frame.
  for (std::size_t i = first_chunk + 20; i < first_chunk + 400; ++i) mcap[i] = '\xff';
  std::vector<std::string> w;
  const std::string skip = dir.Write("skip.mcap", mcap);
  const auto messages = ReadAll(skip, w);
  ASSERT_EQ(messages.size(), kRows);
  ExpectSessionPrefix(messages);
  const BagSummary summary = InspectBag(skip);
  ASSERT_EQ(summary.topics.size(), 2u);
  for (const BagTopic& t : summary.topics)
    EXPECT_EQ(t.messages,
              static_cast<std::int64_t>(t.name == "/chatter" ? kChatterMessages : kRows))
        << t.name;
  // The same damage in a chunk that holds IMU messages is found.
  std::string imu = ReadFile(Bag("imu_chatter_first.mcap"));
  const std::size_t later = FindNth(imu, zstd, 5);
  ASSERT_NE(later, std::string::npos);
  for (std::size_t i = later + 20; i < later + 400; ++i) imu[i] = '\xff';
  EXPECT_THAT(ErrorText([&] { ReadAll(dir.Write("bad.mcap", imu), w); }),
              HasSubstr("bad.mcap: chunk at byte"));
}

TEST(ReadImuMessages, McapUnknownCompressionIsNamed) {
  ScratchDir dir;
  std::string mcap = ReadFile(Bag("imu_cdr_zstd.mcap"));
  const std::string zstd("\x04\0\0\0zstd", 8);  // the length-prefixed name
  int patched = 0;
  for (std::size_t at = mcap.find(zstd); at != std::string::npos;
       at = mcap.find(zstd, at + 1)) {
    mcap.replace(at + 4, 4, "zsth");
    ++patched;
  }
  ASSERT_GT(patched, 1);
  std::vector<std::string> w;
  EXPECT_THAT(ErrorText([&] { ReadAll(dir.Write("zsth.mcap", mcap), w); }),
              ::testing::AllOf(HasSubstr("zsth.mcap: chunk at byte"),
                               HasSubstr("unknown chunk compression 'zsth'")));
}

TEST(ReadImuMessages, McapChunkCrcIsChecked) {
  ScratchDir dir;
  std::string mcap = ReadFile(Bag("imu_ros1.mcap"));  // chunks stored, CRC written
  const std::size_t frame = FindNth(mcap, "imu_link", 3);
  mcap[frame] = 'J';
  std::vector<std::string> w;
  EXPECT_THAT(
      ErrorText([&] { ReadAll(dir.Write("crc.mcap", mcap), w); }),
      ::testing::AllOf(HasSubstr("crc.mcap: chunk at byte"), HasSubstr("CRC-32")));
}

// An lz4 chunk with a CRC is checked by it alone (the LZ4 frame's own
// checksum is skipped): a damaged literal still unpacks, and the CRC finds it.
TEST(ReadImuMessages, McapLz4ChunkDamageIsFoundByTheCrc) {
  ScratchDir dir;
  std::string mcap = ReadFile(Bag("imu_cdr_be_lz4.mcap"));  // @mcap/core, CRC written
  const std::size_t chunk = FindNth(mcap, std::string("\x03\0\0\0lz4", 7), 3);
  const std::size_t literal = mcap.find("imu_link", chunk);
  ASSERT_NE(literal, std::string::npos);
  mcap[literal] = 'J';
  std::vector<std::string> w;
  EXPECT_THAT(
      ErrorText([&] { ReadAll(dir.Write("lz4crc.mcap", mcap), w); }),
      ::testing::AllOf(HasSubstr("lz4crc.mcap: chunk at byte"), HasSubstr("CRC-32")));
}

// A ROS 1 chunk has no CRC: its LZ4 frame's content checksum (XXH32) is the
// only guard. A damaged literal still unpacks to the chunk's size, and the
// checksum finds it.
TEST(ReadImuMessages, Ros1Lz4ChunkDamageIsFoundByTheFrameChecksum) {
  ScratchDir dir;
  std::string bag = ReadFile(Bag("imu_lz4.bag"));  // rosbag's roslz4 frames
  const std::size_t chunk = FindNth(bag, "compression=lz4", 3);
  const std::size_t literal = bag.find("imu_link", chunk);
  ASSERT_NE(literal, std::string::npos);
  std::vector<std::string> w;
  // Undamaged, the frame's checksum holds.
  EXPECT_EQ(ReadAll(dir.Write("good.bag", bag), w).size(), kRows);
  bag[literal] = 'J';
  EXPECT_THAT(ErrorText([&] { ReadAll(dir.Write("xxh.bag", bag), w); }),
              ::testing::AllOf(HasSubstr("xxh.bag: chunk at byte"),
                               HasSubstr("content checksum")));
}

// A chunk that claims more than the cap is refused before anything is
// allocated for it.
TEST(ReadImuMessages, AChunkSizeAboveTheCapIsRefused) {
  ScratchDir dir;
  std::string bag = ReadFile(Bag("imu_lz4.bag"));
  const std::size_t chunk = FindNth(bag, "compression=lz4", 3);
  const std::size_t size_at = bag.find("size=", chunk) + 5;
  bag.replace(size_at, 4, "\xff\xff\xff\xff");
  std::vector<std::string> w;
  EXPECT_THAT(ErrorText([&] { ReadAll(dir.Write("huge.bag", bag), w); }),
              ::testing::AllOf(HasSubstr("chunk at byte"), HasSubstr("above the cap")));
}

// The container fuzz targets' seed corpora, replayed: each file is read or
// refused with an mpcal::Error, nothing else.
TEST(ReadImuMessages, FuzzSeedsAreReadOrRefused) {
  int files = 0;
  for (const char* target : {"ros1_bag", "mcap_bag"}) {
    const std::filesystem::path seeds =
        std::filesystem::path(MPCAL_TEST_DATA_DIR) / ".." / "fuzz" / target;
    for (const auto& entry : std::filesystem::directory_iterator(seeds)) {
      std::vector<std::string> w;
      try {
        InspectBag(entry.path().string());
        ReadAll(entry.path().string(), w);
      } catch (const mpcal::Error&) {
      }
      ++files;
    }
  }
  EXPECT_GE(files, 8);
}

}  // namespace
}  // namespace mpcal
