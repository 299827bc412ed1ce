// Inspect: a recording's topics and the range of its IMU readings, a text
// log's layout and rows, and the units their magnitudes look like. The
// ranges are checked against the session's CSV, computed here.
#include "mpcal/inspect.h"

#include <cmath>
#include <string>

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

struct Expected {
  Eigen::Vector3d min;
  Eigen::Vector3d max;
  double mean_norm = 0.0;
};

Expected RangeOf(const std::vector<Eigen::Vector3d>& v) {
  Expected e{v.front(), v.front(), 0.0};
  for (const Eigen::Vector3d& x : v) {
    for (int k = 0; k < 3; ++k) {
      e.min[k] = std::min(e.min[k], x[k]);
      e.max[k] = std::max(e.max[k], x[k]);
    }
    e.mean_norm += std::sqrt(x.x() * x.x() + x.y() * x.y() + x.z() * x.z());
  }
  e.mean_norm /= static_cast<double>(v.size());
  return e;
}

void ExpectRange(const ReadingRange& got, const std::vector<Eigen::Vector3d>& rows) {
  const Expected want = RangeOf(rows);
  EXPECT_EQ(got.count, rows.size());
  EXPECT_EQ(got.min, want.min);
  EXPECT_EQ(got.max, want.max);
  EXPECT_NEAR(got.mean_norm(), want.mean_norm, 1e-12 * want.mean_norm);
}

TEST(Inspect, ARecordingsTopicsAndItsImuReadings) {
  const Recording csv = ReadLog(Bag("session.csv"), LogOptions{});
  for (const char* file : {"imu_lz4.bag", "imu_cdr_zstd.mcap", "imu_ros2"}) {
    const Inspection in = Inspect(Bag(file), LogOptions{});
    ASSERT_TRUE(in.is_recording) << file;
    ASSERT_EQ(in.bag.topics.size(), 2u) << file;
    ASSERT_EQ(in.imu.size(), 1u) << file;
    const ImuTopicInspection& t = in.imu.front();
    EXPECT_EQ(t.topic, "/imu/data");
    EXPECT_EQ(t.messages, 380u);
    // Stamps 1700000000 s + t, t from 0 to 18.95 s: 379 steps of 50 ms.
    EXPECT_EQ(t.first_stamp_ns, 1700000000000000000);
    EXPECT_EQ(t.last_stamp_ns, 1700000018950000000);
    EXPECT_NEAR(t.rate_hz, 20.0, 1e-9);
    ExpectRange(t.accel_mps2, csv.accel);
    ExpectRange(t.gyro_radps, csv.gyro_radps);
    EXPECT_EQ(t.accel_look, AccelUnitsLook::kFits);
    EXPECT_EQ(t.gyro_look, GyroUnitsLook::kFits);
    // Rows 100 and 101's stamps swapped; the receive times in order.
    EXPECT_EQ(t.stamp_order.out_of_order, 1u);
    EXPECT_NEAR(t.stamp_order.worst_back_s, 0.05, 1e-12);
    EXPECT_EQ(t.receive_order.out_of_order, 0u);
  }
}

TEST(Inspect, TheTopicAskedForAloneIsRead) {
  LogOptions o;
  o.topic = "/chatter";
  try {
    Inspect(Bag("imu_lz4.bag"), o);
    ADD_FAILURE() << "inspected";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("std_msgs/String"));
  }
  o.topic = "/imu/data";
  EXPECT_EQ(Inspect(Bag("imu_lz4.bag"), o).imu.size(), 1u);
}

TEST(Inspect, TheShuffledBagCountsWhatTheScriptDid) {
  const ImuTopicInspection t = Inspect(Bag("imu_shuffled.bag"), LogOptions{}).imu.front();
  EXPECT_EQ(t.messages, 388u);  // 380 rows, 4 copies, 4 impostors
  EXPECT_EQ(t.stamp_order.out_of_order, 22u);
  EXPECT_NEAR(t.stamp_order.worst_back_s, 1.9, 1e-12);
  EXPECT_EQ(t.receive_order.out_of_order, 0u);
}

TEST(Inspect, ATextLogsLayoutAndRows) {
  const Recording csv = ReadLog(Bag("session.csv"), LogOptions{});
  const Inspection in = Inspect(Bag("session.csv"), LogOptions{});
  ASSERT_FALSE(in.is_recording);
  const LogInspection& log = in.log;
  EXPECT_EQ(log.layout.header_line, 1u);
  EXPECT_EQ(log.layout.time_column, 0);
  EXPECT_TRUE(log.layout.has_gyro());
  EXPECT_EQ(log.rows, 380u);
  EXPECT_EQ(log.first_time_s, 0.0);
  EXPECT_EQ(log.last_time_s, 18.95);
  EXPECT_NEAR(log.rate_hz, 20.0, 1e-9);
  EXPECT_EQ(log.time_not_increasing, 0u);
  ExpectRange(log.accel, csv.accel);
  ExpectRange(log.gyro, csv.gyro_radps);
  EXPECT_EQ(log.accel_look, AccelUnitsLook::kFits);

  // The same numbers declared in g: about 9.8 g at rest is m/s².
  LogOptions g;
  g.units = AccelUnits::kG;
  EXPECT_EQ(Inspect(Bag("session.csv"), g).log.accel_look, AccelUnitsLook::kLikeMps2);
}

ReadingRange Around(double magnitude) {
  ReadingRange r;
  r.Add(Eigen::Vector3d(0.0, 0.0, magnitude));
  r.Add(Eigen::Vector3d(magnitude, 0.0, 0.0));
  return r;
}

// CheckUnits' band (0.5-1.6 g) on the mean magnitude, in the declared units.
TEST(Inspect, TheMagnitudeSaysTheUnits) {
  EXPECT_EQ(LookOfAccel(Around(9.81), AccelUnits::kMps2), AccelUnitsLook::kFits);
  EXPECT_EQ(LookOfAccel(Around(1.0), AccelUnits::kMps2), AccelUnitsLook::kLikeG);
  EXPECT_EQ(LookOfAccel(Around(1.0), AccelUnits::kG), AccelUnitsLook::kFits);
  EXPECT_EQ(LookOfAccel(Around(9.81), AccelUnits::kG), AccelUnitsLook::kLikeMps2);
  EXPECT_EQ(LookOfAccel(Around(1000.0), AccelUnits::kMps2), AccelUnitsLook::kLikeCounts);
  EXPECT_EQ(LookOfAccel(Around(3.0), AccelUnits::kMps2), AccelUnitsLook::kNeither);
  EXPECT_EQ(LookOfAccel(Around(1000.0), AccelUnits::kCounts), AccelUnitsLook::kNotJudged);
  EXPECT_EQ(LookOfAccel(ReadingRange{}, AccelUnits::kMps2), AccelUnitsLook::kNotJudged);
  // 70 rad/s (4000 deg/s) is the largest MEMS full scale.
  EXPECT_EQ(LookOfGyro(Around(60.0), GyroUnits::kRadps), GyroUnitsLook::kFits);
  EXPECT_EQ(LookOfGyro(Around(300.0), GyroUnits::kRadps), GyroUnitsLook::kLikeDps);
  EXPECT_EQ(LookOfGyro(Around(300.0), GyroUnits::kDps), GyroUnitsLook::kFits);
  EXPECT_EQ(LookOfGyro(Around(5000.0), GyroUnits::kRadps), GyroUnitsLook::kLikeCounts);
}

TEST(Inspect, ARecordingRefusesTextLogOptions) {
  LogOptions g;
  g.units = AccelUnits::kG;
  EXPECT_THROW(Inspect(Bag("imu_lz4.bag"), g), Error);
}

}  // namespace
}  // namespace mpcal
