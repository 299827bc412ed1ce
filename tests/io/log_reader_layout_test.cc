// Layout detection on its own: first bytes in, a layout out, no file.
#include "io/log_layout.h"

#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mpcal/error.h"

namespace mpcal::logio {
namespace {

using ::testing::ElementsAre;
using ::testing::HasSubstr;

DetectedLayout Detect(const std::string& head, LogOptions options = {}) {
  return DetectLayout(head, /*whole_input=*/true, "log", options, /*parse_gyro=*/true);
}

Error DetectFailure(const std::string& head, LogOptions options = {}) {
  try {
    Detect(head, options);
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "no error for:\n" << head;
  return Error("");
}

TEST(LogLayout, SemicolonsAndDecimalCommas) {
  const auto d = Detect("time;ax;ay;az\n0,00;0,1;0,2;9,8\n0,01;0,1;0,2;9,8\n");
  EXPECT_EQ(d.layout.delimiter, ';');
  EXPECT_EQ(d.layout.decimal_point, ',');
  EXPECT_EQ(d.layout.header_line, 1u);
  EXPECT_EQ(d.layout.time_column, 0);
  EXPECT_THAT(d.layout.accel_columns, ElementsAre(1, 2, 3));
  EXPECT_THAT(d.roles, ElementsAre(kTime, kAx, kAy, kAz));
}

TEST(LogLayout, AlignedTabsAreBlanksAndGyroscopeFound) {
  const auto d = Detect("t\t\tax\tay\taz\tgx\tgy\tgz\n0\t\t1\t2\t3\t4\t5\t6\n");
  EXPECT_EQ(d.layout.delimiter, ' ');
  EXPECT_TRUE(d.layout.has_gyro());
  EXPECT_EQ(d.layout.min_columns, 7);
}

TEST(LogLayout, UnneededColumnsAreNotParsed) {
  const auto d = Detect("t,temp,ax,ay,az,status\n0,21,1,2,3,ok\n");
  EXPECT_THAT(d.roles, ElementsAre(kTime, kNone, kAx, kAy, kAz));
  EXPECT_EQ(d.layout.min_columns, 5);  // the status column is never read
}

TEST(LogLayout, IntegerTimestampsTakeTheUnitOfAnImuPeriod) {
  // 10,000 units a sample: µs at 100 Hz (not ns at 100 kHz, not ms at 0.1 Hz).
  std::string log = "t,ax,ay,az\n";
  for (int i = 0; i < 20; ++i) log += std::to_string(1000000 + 10000 * i) + ",0,0,9.8\n";
  const auto d = Detect(log);
  EXPECT_EQ(d.layout.time_unit, TimeUnit::kMicroseconds);
  EXPECT_DOUBLE_EQ(d.layout.seconds_per_time_unit, 1e-6);
  ASSERT_EQ(d.warnings.size(), 1u);
  EXPECT_THAT(d.warnings[0], HasSubstr("taken as us"));
}

TEST(LogLayout, NamedTimeUnitWins) {
  const auto d = Detect("millis,ax,ay,az\n0,0,0,1\n1,0,0,1\n2,0,0,1\n");
  EXPECT_EQ(d.layout.time_unit, TimeUnit::kMilliseconds);
  EXPECT_TRUE(d.warnings.empty());
}

TEST(LogLayout, BootTextIsSkippedWithItsBytes) {
  const std::string boot = "Initializing I2C devices...\nMPU6050 connection successful\n";
  const auto d = Detect(boot + "t,ax,ay,az\n0.00,0,0,1\n0.01,0,0,1\n0.02,0,0,1\n");
  EXPECT_EQ(d.skipped_lines, 2u);
  EXPECT_EQ(d.skipped_bytes, boot.size());
  EXPECT_EQ(d.layout.header_line, 3u);
  ASSERT_EQ(d.warnings.size(), 1u);
  EXPECT_THAT(d.warnings[0], HasSubstr("the header starts on line 3"));
}

TEST(LogLayout, ByteOrderMarkIsNotData) {
  const auto d = Detect("\xEF\xBB\xBFt,ax,ay,az\n0,0,0,1\n");
  EXPECT_EQ(d.bom_bytes, 3u);
  EXPECT_EQ(d.layout.column_names[0], "t");
}

TEST(LogLayout, FailuresCarryTheOptionThatWouldFixThem) {
  const Error counter = DetectFailure(
      "t,ax,ay,az\n0,0,0,1\n1,0,0,1\n2,0,0,1\n3,0,0,1\n"
      "4,0,0,1\n5,0,0,1\n6,0,0,1\n7,0,0,1\n8,0,0,1\n");
  EXPECT_EQ(counter.kind(), ErrorKind::kTime);
  EXPECT_THAT(counter.what(), HasSubstr("steps by exactly 1"));
  ASSERT_FALSE(counter.advice().settings.empty());
  EXPECT_EQ(counter.advice().settings[0].option, Option::kLogRate);

  const Error missing = DetectFailure("t,ax,ay\n0,0,0\n");
  EXPECT_EQ(missing.kind(), ErrorKind::kColumns);
  EXPECT_THAT(missing.what(), HasSubstr("no column for az in the header (line 1)"));
  ASSERT_EQ(missing.advice().settings.size(), 1u);
  EXPECT_EQ(missing.advice().settings[0].option, Option::kLogColumns);
  EXPECT_EQ(missing.advice().settings[0].value, "az=NAME|INDEX");

  const Error binary = DetectFailure(std::string("ab\0cd", 5));
  EXPECT_THAT(binary.what(), HasSubstr("binary data at byte 2"));
}

TEST(LogLayout, NoMessageNamesAFlag) {
  LogOptions options;
  options.columns = "t=1,ax=nope";
  for (const auto& e : {DetectFailure("1 2 3 4\n5 6 7 8\n", options),
                        DetectFailure("n_samples,ax,ay,az\n0,1,2,3\n"),
                        DetectFailure("a,b,c\n1,2,3\n")}) {
    EXPECT_THAT(e.what(), ::testing::Not(HasSubstr("--"))) << e.what();
    EXPECT_FALSE(e.advice().empty()) << e.what();
  }
}

}  // namespace
}  // namespace mpcal::logio
