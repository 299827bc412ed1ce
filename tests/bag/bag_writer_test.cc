// RewriteImuMessages against the fixtures (tests/data/bags/, written by
// Debian's rosbag and Foxglove's @mcap/core): what it writes is read back by
// mpcal's readers here; tests/cli/apply_bag_*.{py,mjs} read it with rosbag
// and @mcap/core themselves.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <streambuf>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mpcal/bag.h"
#include "mpcal/error.h"
#include "test_util.h"

namespace mpcal {
namespace {

using ::testing::HasSubstr;
using testing::ReadFile;
using testing::ScratchDir;

std::string Fixture(const std::string& name) {
  return testing::TestDataPath("bags/" + name);
}

std::vector<ImuMessage> ReadBack(const std::string& path,
                                 std::vector<std::string>& warnings) {
  std::vector<ImuMessage> all;
  ReadImuMessages(
      path,
      "/imu/data",
      [&](std::span<const ImuMessage> batch) {
        all.insert(all.end(), batch.begin(), batch.end());
      },
      warnings);
  return all;
}

// Writes `input` rewritten by `edit` to `name` in `dir`; returns its path.
std::string Rewrite(const ScratchDir& dir,
                    const std::string& input,
                    const std::string& name,
                    const ImuEdit& edit,
                    std::vector<std::string>& warnings,
                    BagRewriteResult* result = nullptr) {
  std::ofstream out(dir.Path(name), std::ios::binary);
  const BagRewriteResult r = RewriteImuMessages(input, out, "/imu/data", edit, warnings);
  if (result) *result = r;
  out.close();
  return dir.Path(name);
}

const Eigen::Vector3d kAccelStep(0.25, -0.5, 1.0);
const Eigen::Vector3d kGyroStep(0.01, 0.02, -0.03);

void Shift(ImuMessage& m) {
  m.linear_acceleration_mps2 += kAccelStep;
  m.angular_velocity_radps += kGyroStep;
}

class EveryWritable : public ::testing::TestWithParam<const char*> {};

// Each message read back is the input's with the edit applied, exactly (the
// doubles are written as doubles), with its stamps; every topic keeps its
// type, encoding, count and times; the compression is the input's.
TEST_P(EveryWritable, ReadsBackAsTheInputEdited) {
  ScratchDir dir;
  const std::string input = Fixture(GetParam());
  std::vector<std::string> w_in, w_out, w_write;
  const std::vector<ImuMessage> before = ReadBack(input, w_in);
  BagRewriteResult result;
  const std::string out =
      Rewrite(dir, input, std::string("out_") + GetParam(), Shift, w_write, &result);
  const std::vector<ImuMessage> after = ReadBack(out, w_out);
  EXPECT_THAT(w_write, ::testing::IsEmpty());
  EXPECT_THAT(w_out, ::testing::IsEmpty());
  ASSERT_EQ(after.size(), before.size());
  EXPECT_EQ(result.imu_messages, static_cast<std::int64_t>(before.size()));
  for (std::size_t i = 0; i < before.size(); ++i) {
    SCOPED_TRACE("message " + std::to_string(i));
    EXPECT_EQ(after[i].stamp_ns, before[i].stamp_ns);
    EXPECT_EQ(after[i].receive_ns, before[i].receive_ns);
    EXPECT_EQ(after[i].linear_acceleration_mps2,
              Eigen::Vector3d(before[i].linear_acceleration_mps2 + kAccelStep));
    EXPECT_EQ(after[i].angular_velocity_radps,
              Eigen::Vector3d(before[i].angular_velocity_radps + kGyroStep));
    if (HasFailure()) return;
  }
  const BagSummary in = InspectBag(input);
  const BagSummary written = InspectBag(out);
  EXPECT_EQ(written.format, in.format);
  ASSERT_EQ(written.topics.size(), in.topics.size());
  for (std::size_t i = 0; i < in.topics.size(); ++i) {
    EXPECT_EQ(written.topics[i].name, in.topics[i].name);
    EXPECT_EQ(written.topics[i].type, in.topics[i].type);
    EXPECT_EQ(written.topics[i].encoding, in.topics[i].encoding);
    EXPECT_EQ(written.topics[i].messages, in.topics[i].messages);
    EXPECT_EQ(written.topics[i].first_ns, in.topics[i].first_ns);
    EXPECT_EQ(written.topics[i].last_ns, in.topics[i].last_ns);
    EXPECT_EQ(result.other_messages + result.imu_messages, [&] {
      std::int64_t n = 0;
      for (const BagTopic& t : in.topics) n += t.messages;
      return n;
    }());
  }
  if (!in.compressions.empty()) {
    EXPECT_EQ(written.compressions, in.compressions);
  }
}

INSTANTIATE_TEST_SUITE_P(Fixtures,
                         EveryWritable,
                         ::testing::Values("imu_none.bag",
                                           "imu_bz2.bag",
                                           "imu_lz4.bag",
                                           "imu_cdr_zstd.mcap",
                                           "imu_cdr_be_lz4.mcap",
                                           "imu_ros1.mcap",
                                           "imu_cdr_plain.mcap"));

// Debian's rosbag wrote the bag with stored chunks; rewritten with no
// change, every byte comes out as rosbag wrote it: the bag header and its
// padding, the chunks, the index data, connection and chunk info records.
TEST(RewriteImuMessages, Ros1WithNoChangeIsRosbagsFileByteForByte) {
  ScratchDir dir;
  std::vector<std::string> w;
  const std::string out = Rewrite(
      dir, Fixture("imu_none.bag"), "same.bag", [](ImuMessage&) {}, w);
  EXPECT_TRUE(ReadFile(out) == ReadFile(Fixture("imu_none.bag")));
}

// A bag that was not closed has no index: its chunks are copied up to the
// cut, and the bag written is indexed.
TEST(RewriteImuMessages, Ros1CutShortComesOutClosed) {
  ScratchDir dir;
  const std::string bag = ReadFile(Fixture("imu_lz4.bag"));
  const std::string cut = dir.Write("cut.bag", bag.substr(0, bag.size() / 2));
  std::vector<std::string> w_cut, w_write, w_out;
  const auto before = ReadBack(cut, w_cut);
  const std::string out = Rewrite(
      dir, cut, "closed.bag", [](ImuMessage&) {}, w_write);
  EXPECT_THAT(w_write, ::testing::Contains(HasSubstr("lies past the end of the file")));
  EXPECT_THAT(w_write, ::testing::Contains(HasSubstr("cut short")));
  const auto after = ReadBack(out, w_out);
  EXPECT_THAT(w_out, ::testing::IsEmpty());
  ASSERT_EQ(after.size(), before.size());
  EXPECT_GT(after.size(), 50u);
}

TEST(RewriteImuMessages, McapCutShortComesOutClosed) {
  ScratchDir dir;
  const std::string mcap = ReadFile(Fixture("imu_cdr_zstd.mcap"));
  const std::string cut = dir.Write("cut.mcap", mcap.substr(0, mcap.size() / 2));
  std::vector<std::string> w_cut, w_write, w_out;
  const auto before = ReadBack(cut, w_cut);
  const std::string out = Rewrite(
      dir, cut, "closed.mcap", [](ImuMessage&) {}, w_write);
  EXPECT_THAT(w_write, ::testing::Contains(HasSubstr("no footer")));
  const auto after = ReadBack(out, w_out);
  EXPECT_THAT(w_out, ::testing::IsEmpty());
  ASSERT_EQ(after.size(), before.size());
  EXPECT_GT(after.size(), 50u);
}

std::string ErrorOf(const std::string& input, const std::string& topic) {
  std::ostringstream out;
  std::vector<std::string> w;
  try {
    RewriteImuMessages(
        input, out, topic, [](ImuMessage&) {}, w);
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

TEST(RewriteImuMessages, RefusesATopicOfAnotherTypeOrAbsent) {
  EXPECT_THAT(ErrorOf(Fixture("imu_lz4.bag"), "/chatter"),
              HasSubstr("topic '/chatter' is of type std_msgs/String"));
  EXPECT_THAT(ErrorOf(Fixture("imu_cdr_zstd.mcap"), "/chatter"),
              HasSubstr("topic '/chatter' holds std_msgs/msg/String"));
  EXPECT_THAT(ErrorOf(Fixture("imu_none.bag"), "/imu"),
              HasSubstr("no topic '/imu'; the bag holds /chatter (std_msgs/String), "
                        "/imu/data (sensor_msgs/Imu)"));
  EXPECT_THAT(ErrorOf(Fixture("imu_ros1.mcap"), "/imu"), HasSubstr("no topic '/imu'"));
  EXPECT_THAT(ErrorOf(Fixture("imu_ros2"), "/imu/data"),
              HasSubstr("a ROS 2 bag is read but not written"));
}

// Damaged recordings whose copy would read otherwise (its index or summary
// lists each connection once, so a message copied unedited before its
// record would read as an IMU message, and an id given two topics as one of
// them) are refused by the writer, in one line naming the record.
TEST(RewriteImuMessages, RefusesARecordingWhoseCopyWouldReadOtherwise) {
  EXPECT_THAT(ErrorOf(Fixture("connection_after_message.bag"), "/imu/data"),
              HasSubstr("connection_after_message.bag: chunk at byte 4117: a message of "
                        "connection 0 comes before the connection's record"));
  EXPECT_THAT(ErrorOf(Fixture("connection_given_twice.bag"), "/imu/data"),
              HasSubstr("connection 0 is given twice, as '/chatter' (std_msgs/String) "
                        "and as '/imu/data' (sensor_msgs/Imu)"));
  EXPECT_THAT(ErrorOf(Fixture("damaged_reads_back_otherwise.mcap"), "/imu/data"),
              HasSubstr("record at byte 251: a message of channel 0 comes before the "
                        "channel's record (topic '/imu/data')"));
}

// A stream that cannot seek back (a pipe) cannot take a ROS 1 bag, whose
// header is completed at the end: refused before anything is written.
TEST(RewriteImuMessages, Ros1NeedsAStreamThatSeeks) {
  struct Pipe : std::streambuf {
    std::string bytes;
    int_type overflow(int_type c) override {
      bytes += static_cast<char>(c);
      return c;
    }
  } pipe;
  std::ostream out(&pipe);
  std::vector<std::string> w;
  try {
    RewriteImuMessages(Fixture("imu_none.bag"), out, "/imu/data", Shift, w);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("not to a pipe"));
  }
  EXPECT_TRUE(pipe.bytes.empty());
}

// The fuzz target's invariant on its seeds: whatever is rewritten reads
// back whole, every message edited.
TEST(RewriteImuMessages, FuzzSeedsRewrittenReadBackOrAreRefused) {
  ScratchDir dir;
  int rewritten = 0;
  for (const char* target : {"ros1_bag", "mcap_bag"}) {
    const std::filesystem::path seeds =
        std::filesystem::path(MPCAL_TEST_DATA_DIR) / ".." / "fuzz" / target;
    for (const auto& entry : std::filesystem::directory_iterator(seeds)) {
      SCOPED_TRACE(entry.path().string());
      std::vector<std::string> w_write, w_read;
      BagRewriteResult result;
      std::string out;
      try {
        out = Rewrite(dir, entry.path().string(), "out", Shift, w_write, &result);
      } catch (const Error&) {
        continue;
      }
      EXPECT_EQ(static_cast<std::int64_t>(ReadBack(out, w_read).size()),
                result.imu_messages);
      ++rewritten;
    }
  }
  EXPECT_GE(rewritten, 4);
}

}  // namespace
}  // namespace mpcal
