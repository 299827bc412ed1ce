// A recording read as a log (ReadLog, ReadLogRows): its messages put in time
// order and counted, the row sink's other rules applied, and the options
// that describe text logs refused.
#include <filesystem>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "bag_fixture.h"
#include "mpcal/error.h"
#include "mpcal/log_reader.h"
#include "test_util.h"

namespace mpcal {
namespace {

using ::testing::HasSubstr;

using testing::Bag;

Recording SessionCsv() { return ReadLog(Bag("session.csv"), LogOptions{}); }

// The fixtures' header stamps of rows 100 and 101 are swapped: read at the
// stamps, the two messages are put in time order (row 101's readings at
// 5 s, row 100's at 5.05 s), and the one late message is counted, 50 ms
// back. Every other row is the CSV's, exactly.
TEST(ReadLogOfABag, StampsOutOfOrderAreSortedAndCounted) {
  const Recording csv = SessionCsv();
  for (const char* file : {"imu_ros2", "imu_lz4.bag", "imu_cdr_zstd.mcap"}) {
    const Recording rec = ReadLog(Bag(file), LogOptions{});
    ASSERT_EQ(rec.size(), csv.size()) << file;
    EXPECT_EQ(rec.time_s, csv.time_s) << file;
    for (std::size_t i = 0; i < rec.size(); ++i) {
      const std::size_t row = i == 100 ? 101 : i == 101 ? 100 : i;
      ASSERT_EQ(rec.accel[i], csv.accel[row]) << file << " row " << i;
      ASSERT_EQ(rec.gyro_radps[i], csv.gyro_radps[row]) << file << " row " << i;
    }
    EXPECT_EQ(rec.stamp_order.out_of_order, 1u) << file;
    EXPECT_NEAR(rec.stamp_order.worst_back_s, 0.05, 1e-15) << file;
    EXPECT_EQ(rec.stamp_order.duplicated, 0u);
    EXPECT_EQ(rec.stamp_order.same_time_other_readings, 0u);
    ASSERT_FALSE(rec.warnings.empty()) << file;
    EXPECT_THAT(
        rec.warnings,
        ::testing::Contains(HasSubstr("1 message out of order (the furthest 50 ms back) "
                                      "put in time order")))
        << file;
  }
}

// The receive times (2 ms after each row's own time, in row order) give
// the CSV exactly: its times, its readings, nothing out of order.
TEST(ReadLogOfABag, ReceiveTimeGivesTheRecordersOrder) {
  const Recording csv = SessionCsv();
  LogOptions receive;
  receive.recording_time = RecordingTime::kReceive;
  for (const char* file : {"imu_ros2", "imu_lz4.bag", "imu_cdr_zstd.mcap"}) {
    const Recording rec = ReadLog(Bag(file), receive);
    EXPECT_EQ(rec.time_s, csv.time_s) << file;
    EXPECT_EQ(rec.accel, csv.accel) << file;
    EXPECT_EQ(rec.gyro_radps, csv.gyro_radps) << file;
    EXPECT_FALSE(rec.stamp_order.changed()) << file;
  }
}

// make_ros1_shuffled.py wrote the session's rows late, twice, and with
// impostors at their stamps, and printed what it did: "out_of_order=22
// worst_back_ms=1900 duplicated=4 same_time_other_readings=4". Read, they
// are the CSV's rows exactly, and the counts are the script's.
TEST(ReadLogOfABag, ShuffledAndDuplicatedStampsGiveTheSortedRows) {
  const Recording csv = SessionCsv();
  const Recording rec = ReadLog(Bag("imu_shuffled.bag"), LogOptions{});
  EXPECT_EQ(rec.time_s, csv.time_s);
  EXPECT_EQ(rec.accel, csv.accel);
  EXPECT_EQ(rec.gyro_radps, csv.gyro_radps);
  EXPECT_EQ(rec.stamp_order.out_of_order, 22u);
  EXPECT_NEAR(rec.stamp_order.worst_back_s, 1.9, 1e-15);
  EXPECT_EQ(rec.stamp_order.duplicated, 4u);
  EXPECT_EQ(rec.stamp_order.same_time_other_readings, 4u);

  // Streamed, the same rows in pieces and the same counts.
  Recording streamed;
  const LogStreamSummary s =
      ReadLogRows(Bag("imu_shuffled.bag"), LogOptions{}, [&](const Recording& rows) {
        streamed.time_s.insert(
            streamed.time_s.end(), rows.time_s.begin(), rows.time_s.end());
        streamed.accel.insert(streamed.accel.end(), rows.accel.begin(), rows.accel.end());
      });
  EXPECT_EQ(streamed.time_s, csv.time_s);
  EXPECT_EQ(streamed.accel, csv.accel);
  EXPECT_EQ(s.rows, csv.size());
  EXPECT_EQ(s.stamp_order.out_of_order, 22u);
  EXPECT_EQ(s.stamp_order.duplicated, 4u);
  EXPECT_EQ(s.stamp_order.same_time_other_readings, 4u);
  EXPECT_EQ(s.warnings, rec.warnings);
}

TEST(ReadLogOfABag, ATextLogHasNoReceiveTime) {
  LogOptions receive;
  receive.recording_time = RecordingTime::kReceive;
  try {
    ReadLog(Bag("session.csv"), receive);
    ADD_FAILURE() << "read";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kOption);
    EXPECT_THAT(e.what(), HasSubstr("a text log has one time"));
    ASSERT_EQ(e.advice().settings.size(), 1u);
    EXPECT_EQ(e.advice().settings[0].option, Option::kLogRecordingTime);
  }
  EXPECT_THROW(LogScanner(Bag("session.csv"), receive), Error);
}

TEST(ReadLogOfABag, RowsAreHandedOverInSiUnits) {
  std::vector<double> times;
  std::vector<Eigen::Vector3d> accel;
  ReadLogRows(Bag("imu_ros2"), LogOptions{}, [&](const Recording& rows) {
    EXPECT_EQ(rows.units, AccelUnits::kMps2);
    EXPECT_EQ(rows.gyro_radps.size(), rows.size());
    times.insert(times.end(), rows.time_s.begin(), rows.time_s.end());
    accel.insert(accel.end(), rows.accel.begin(), rows.accel.end());
  });
  ASSERT_EQ(times.size(), 380u);
  EXPECT_EQ(times[0], 0.0);
  EXPECT_NEAR(times[101], 5.05, 1e-12);
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
  const LogStreamSummary summary =
      ReadLogRows(dir.Write("no_gyro.bag", bag), LogOptions{}, [&](const Recording& r) {
        EXPECT_TRUE(r.gyro_radps.empty());
        rows += r.size();
      });
  EXPECT_EQ(rows, 380u);
  EXPECT_FALSE(summary.has_gyro);
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
