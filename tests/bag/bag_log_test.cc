// A recording read as a log (ReadLog, ReadLogRows): the row sink's rules
// apply to its messages, and the options that describe text logs are refused.
#include <filesystem>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mpcal/error.h"
#include "mpcal/log_reader.h"
#include "test_util.h"

namespace mpcal {
namespace {

using ::testing::HasSubstr;

std::string Bag(const std::string& name) { return testing::TestDataPath("bags/" + name); }

// The fixtures' header stamps of rows 100 and 101 are swapped: as a log, the
// message after them goes back in time, and the error counts messages.
TEST(ReadLogOfABag, StampsOutOfOrderAreTimeGoingBack) {
  for (const char* file : {"imu_ros2", "imu_lz4.bag", "imu_cdr_zstd.mcap"}) {
    try {
      ReadLog(Bag(file), LogOptions{});
      ADD_FAILURE() << file << " was read";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::kTime);
      EXPECT_THAT(e.what(),
                  HasSubstr(":102: time goes back: 5 s after 5.05 s on message 101"))
          << file;
    }
  }
}

TEST(ReadLogOfABag, RowsBeforeTheErrorAreHandedOverInSiUnits) {
  std::vector<double> times;
  std::vector<Eigen::Vector3d> accel;
  try {
    ReadLogRows(Bag("imu_ros2"), LogOptions{}, [&](const Recording& rows) {
      EXPECT_EQ(rows.units, AccelUnits::kMps2);
      EXPECT_EQ(rows.gyro_radps.size(), rows.size());
      times.insert(times.end(), rows.time_s.begin(), rows.time_s.end());
      accel.insert(accel.end(), rows.accel.begin(), rows.accel.end());
    });
  } catch (const Error&) {
  }
  ASSERT_EQ(times.size(), 101u);  // messages 1..101, in time order
  EXPECT_EQ(times[0], 0.0);
  EXPECT_NEAR(times[100], 5.05, 1e-12);
  // session.csv's first row.
  EXPECT_EQ(accel[0],
            Eigen::Vector3d(-0.7171451816101523, 0.14835904307160247, 9.624971347565719));
}

// Each message of the copy marks its angular velocity as not measured
// (angular_velocity_covariance[0] = -1, 128 bytes after the frame id: 13
// doubles of orientation and its covariance, 3 of angular velocity); the
// bag then has no gyroscope, not a gyroscope reading zero.
TEST(ReadLogOfABag, AngularVelocityNotMeasuredGivesNoGyroscope) {
  testing::ScratchDir dir;
  std::string bag = testing::ReadFile(Bag("imu_none.bag"));  // chunks stored
  const std::string frame("\x08\0\0\0imu_link", 12);
  const double minus_one = -1.0;
  int patched = 0;
  for (std::size_t at = bag.find(frame); at != std::string::npos;
       at = bag.find(frame, at + 1)) {
    bag.replace(at + 12 + 128, 8, reinterpret_cast<const char*>(&minus_one), 8);
    ++patched;
  }
  ASSERT_EQ(patched, 380);
  std::size_t rows = 0;
  LogStreamSummary summary;
  try {
    ReadLogRows(dir.Write("no_gyro.bag", bag), LogOptions{}, [&](const Recording& r) {
      EXPECT_TRUE(r.gyro_radps.empty());
      rows += r.size();
    });
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kTime);  // the swapped stamps, as above
  }
  EXPECT_EQ(rows, 101u);
}

TEST(ReadLogOfABag, TextLogOptionsAreRefusedWithTheOption) {
  LogOptions g;
  g.units = AccelUnits::kG;
  LogOptions rate;
  rate.rate_hz = 100.0;
  for (const LogOptions& o : {g, rate}) {
    try {
      ReadLog(Bag("imu_ros2"), o);
      ADD_FAILURE() << "read";
    } catch (const Error& e) {
      EXPECT_EQ(e.kind(), ErrorKind::kOption);
      EXPECT_THAT(e.what(), HasSubstr("are for text logs only"));
    }
  }
}

TEST(ReadLogOfABag, ATopicOfAnotherTypeIsRefused) {
  LogOptions o;
  o.topic = "/chatter";
  EXPECT_THROW(
      {
        try {
          ReadLog(Bag("imu_none.bag"), o);
        } catch (const Error& e) {
          EXPECT_THAT(e.what(), HasSubstr("std_msgs/String"));
          throw;
        }
      },
      Error);
}

TEST(ReadLogOfABag, ARecordingWithNoImuTopicSaysWhatItHolds) {
  EXPECT_THROW(
      {
        try {
          ReadLog(Bag("empty.bag"), LogOptions{});
        } catch (const Error& e) {
          EXPECT_THAT(e.what(),
                      HasSubstr("empty.bag: no sensor_msgs/Imu topic; the "
                                "recording holds none"));
          throw;
        }
      },
      Error);
}

// Two sensor_msgs/Imu topics: the reader does not guess, it names both and
// points at LogOptions::topic. (The copy's /chatter type is rewritten in
// place: "std_msgs/msg/String" and "sensor_msgs/msg/Imu" have one length.)
TEST(ReadLogOfABag, SeveralImuTopicsNeedTheTopicOption) {
  testing::ScratchDir dir;
  std::filesystem::create_directory(dir.path() / "two");
  std::string db = testing::ReadFile(Bag("imu_ros2/imu_ros2_0.db3"));
  const std::size_t at = db.find("std_msgs/msg/String");
  ASSERT_NE(at, std::string::npos);
  db.replace(at, 19, "sensor_msgs/msg/Imu");
  dir.Write("two/two_0.db3", db);
  dir.Write("two/metadata.yaml", "rosbag2_bagfile_information:\n");
  try {
    ReadLog(dir.Path("two"), LogOptions{});
    ADD_FAILURE() << "read";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kOption);
    EXPECT_THAT(e.what(), HasSubstr("2 sensor_msgs/Imu topics (/chatter, /imu/data)"));
    ASSERT_EQ(e.advice().settings.size(), 1u);
    EXPECT_EQ(e.advice().settings[0].option, Option::kLogTopic);
  }
}

TEST(ReadLogOfABag, IsNotRewrittenLineByLine) {
  EXPECT_THROW(LogScanner(Bag("imu_lz4.bag"), LogOptions{}), Error);
}

}  // namespace
}  // namespace mpcal
