// A gyroscope in a file of its own: its header read as a gyroscope's, its own
// column mapping (keys t, gx, gy, gz), and the units the merged recording
// keeps for the calibration file.
#include "mpcal/gyro_log.h"

#include <numbers>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mpcal/error.h"
#include "mpcal/log_reader.h"
#include "test_util.h"

namespace mpcal {
namespace {

using mpcal::testing::ScratchDir;
using ::testing::HasSubstr;

constexpr double kTol = 1e-12;

std::string Rows() { return "0,0.1,0.2,0.3\n0.01,0.4,0.5,0.6\n0.02,0.7,0.8,0.9\n"; }

TEST(ReadGyroLog, TakesTheReadingsByTheHeadersGyroscopeNames) {
  const ScratchDir dir;
  for (const std::string header : {"t,x,y,z",
                                   "t,gx,gy,gz",
                                   "time,wx,wy,wz",
                                   "t,gyr_x,gyr_y,gyr_z",
                                   "Time (s),Gyro_X,Gyro_Y,Gyro_Z",
                                   "t,omega_x,omega_y,omega_z"}) {
    SCOPED_TRACE(header);
    const Recording r = ReadGyroLog(dir.Write("g.csv", header + "\n" + Rows()), {});
    ASSERT_EQ(r.size(), 3u);
    EXPECT_NEAR(r.time_s[2], 0.02, kTol);
    EXPECT_NEAR(r.accel[1].x(), 0.4, kTol);
    EXPECT_NEAR(r.accel[1].z(), 0.6, kTol);
  }
}

TEST(ReadGyroLog, ColumnsInAnotherOrderFollowTheirNames) {
  const ScratchDir dir;
  const Recording r = ReadGyroLog(
      dir.Write("g.csv", "gz,t,gy,gx\n0.3,0,0.2,0.1\n0.6,0.01,0.5,0.4\n"), {});
  ASSERT_EQ(r.size(), 2u);
  EXPECT_NEAR(r.accel[1].x(), 0.4, kTol);
  EXPECT_NEAR(r.accel[1].y(), 0.5, kTol);
  EXPECT_NEAR(r.accel[1].z(), 0.6, kTol);
}

TEST(ReadGyroLog, UnknownNamesAskForTheGyroscopesOwnMapping) {
  const ScratchDir dir;
  const std::string path = dir.Write("g.csv", "clock,a,b,c\n" + Rows());
  try {
    ReadGyroLog(path, {});
    FAIL() << "read a header that names no gyroscope columns";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("the header names no gyroscope columns"));
    ASSERT_FALSE(e.advice().settings.empty());
    EXPECT_EQ(e.advice().settings.front().option, Option::kGyroLogColumns);
  }
  LogOptions mapped;
  mapped.columns = "t=clock,gx=c,gy=b,gz=a";
  const Recording r = ReadGyroLog(path, mapped);
  EXPECT_NEAR(r.accel[2].x(), 0.9, kTol);
  EXPECT_NEAR(r.accel[2].z(), 0.7, kTol);
  // The accelerometer's keys are not a gyroscope's.
  mapped.columns = "t=clock,ax=a,ay=b,az=c";
  EXPECT_THROW(ReadGyroLog(path, mapped), Error);
}

TEST(ReadGyroLog, WithoutHeaderTheColumnsAreTXYZ) {
  const ScratchDir dir;
  const Recording r = ReadGyroLog(dir.Write("g.txt", Rows()), {});
  ASSERT_EQ(r.size(), 3u);
  EXPECT_NEAR(r.accel[0].y(), 0.2, kTol);
}

// The merged recording holds rad/s and remembers the log's deg/s, which a
// calibration made from it records (Recording::gyro_log_units).
TEST(MergeGyroLog, KeepsTheLogsUnitsBesideTheReadingsInRadps) {
  const ScratchDir dir;
  const Recording accel = ReadLog(dir.Write("a.csv", "t,ax,ay,az\n" + Rows()), {});
  LogOptions dps;
  dps.gyro_in_dps = true;
  const Recording gyro = ReadGyroLog(dir.Write("g.csv", "t,x,y,z\n" + Rows()), dps);
  Recording merged = accel;
  MergeGyroLog(merged, gyro, GyroUnits::kDps);
  EXPECT_EQ(merged.gyro_units, GyroUnits::kRadps);
  EXPECT_EQ(merged.gyro_log_units, GyroUnits::kDps);
  EXPECT_NEAR(merged.gyro_radps[1].x(), 0.4 * std::numbers::pi / 180.0, kTol);
}

TEST(ReadLog, RecordsTheGyroscopeColumnsUnitsAsWritten) {
  const ScratchDir dir;
  LogOptions dps;
  dps.gyro_in_dps = true;
  const Recording r = ReadLog(
      dir.Write("imu.csv", "t,ax,ay,az,gx,gy,gz\n0,0,0,9.8,1,2,3\n0.01,0,0,9.8,4,5,6\n"),
      dps);
  EXPECT_EQ(r.gyro_units, GyroUnits::kRadps);
  EXPECT_EQ(r.gyro_log_units, GyroUnits::kDps);
  EXPECT_NEAR(r.gyro_radps[1].z(), 6.0 * std::numbers::pi / 180.0, kTol);
}

}  // namespace
}  // namespace mpcal
