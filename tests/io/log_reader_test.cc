#include "mpcal/log_reader.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mpcal/error.h"
#include "test_util.h"

namespace mpcal {
namespace {

using mpcal::testing::RealDataPath;
using mpcal::testing::ScratchDir;
using mpcal::testing::TestDataPath;
using ::testing::AllOf;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

LogOptions WithUnits(AccelUnits units) {
  LogOptions options;
  options.units = units;
  return options;
}

LogOptions WithTimeUnit(TimeUnit unit) {
  LogOptions options;
  options.time_unit = unit;
  return options;
}

Recording Read(const ScratchDir& dir,
               const std::string& content,
               LogOptions options = {}) {
  return ReadLog(dir.Write("log.txt", content), options);
}

// The message of the mpcal::Error that reading `content` throws.
std::string ReadError(const ScratchDir& dir,
                      const std::string& content,
                      LogOptions options = {}) {
  try {
    Read(dir, content, options);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for:\n" << content;
  return "";
}

// The mpcal::Error that reading `content` throws.
Error ReadFailure(const ScratchDir& dir,
                  const std::string& content,
                  LogOptions options = {}) {
  try {
    Read(dir, content, options);
  } catch (const Error& e) {
    return e;
  }
  ADD_FAILURE() << "no error for:\n" << content;
  return Error("");
}

// The error advises setting `option` (the command line spells it as a flag).
bool Advises(const Error& e, Option option) {
  return std::any_of(e.advice().settings.begin(),
                     e.advice().settings.end(),
                     [option](const Setting& s) { return s.option == option; });
}

TEST(ReadLog, CommaSeparatedWithHeader) {
  ScratchDir dir;
  const Recording r = Read(dir, "t,ax,ay,az\n0.0,0.1,0.2,9.8\n0.01,0.11,-0.2,9.81\n");
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r.time_s[1], 0.01);
  EXPECT_EQ(r.accel[1].x(), 0.11);
  EXPECT_EQ(r.accel[1].y(), -0.2);
  EXPECT_EQ(r.accel[1].z(), 9.81);
  EXPECT_TRUE(r.gyro_radps.empty());
  EXPECT_TRUE(r.warnings.empty());
  EXPECT_EQ(r.units, AccelUnits::kMps2);
}

TEST(ReadLog, HeaderNamesAreCaseInsensitiveAndExtraColumnsIgnored) {
  ScratchDir dir;
  const Recording r = Read(dir,
                           "Temp,TIMESTAMP,accZ,AccX,Acc_Y [m/s2],note\n"
                           "21.5,1.5,9.8,0.1,0.2,x\n"
                           "21.5,1.6,9.7,0.3,0.4,y\n");
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r.time_s[0], 1.5);
  EXPECT_EQ(r.accel[1], Eigen::Vector3d(0.3, 0.4, 9.7));
}

TEST(ReadLog, WhitespaceSeparatedWithoutHeaderIsTimeThenAxes) {
  ScratchDir dir;
  const Recording r =
      Read(dir,
           "   2.9840000e-02   3.3108000e+04   3.3329000e+04   3.6429000e+04\n"
           "\t3.9857000e-02 \t 3.3096000e+04   3.3336000e+04   3.6437000e+04\n",
           WithUnits(AccelUnits::kCounts));
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r.time_s[1], 3.9857e-02);
  EXPECT_EQ(r.accel[0], Eigen::Vector3d(33108, 33329, 36429));
  EXPECT_EQ(r.units, AccelUnits::kCounts);
}

TEST(ReadLog, SemicolonsDecimalCommasCommentsAndCrlf) {
  ScratchDir dir;
  const Recording r = Read(dir,
                           "# logger v2\r\n"
                           "% exported 2024\r\n"
                           "time;ax;ay;az\r\n"
                           "0,5;0,1;-0,25;9,75\r\n"
                           "\r\n"
                           "# a comment in the middle\r\n"
                           "0,6;0,2;-0,5;9,5\r\n");
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r.time_s[0], 0.5);
  EXPECT_EQ(r.accel[0], Eigen::Vector3d(0.1, -0.25, 9.75));
  EXPECT_EQ(r.accel[1], Eigen::Vector3d(0.2, -0.5, 9.5));
}

TEST(ReadLog, TabSeparated) {
  ScratchDir dir;
  const Recording r = Read(
      dir, "t\tax\tay\taz\n1\t2\t3\t4\n2\t5\t6\t7\n", WithTimeUnit(TimeUnit::kSeconds));
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r.accel[1], Eigen::Vector3d(5, 6, 7));
}

TEST(ReadLog, GyroscopeColumnsInDegreesPerSecond) {
  ScratchDir dir;
  LogOptions options;
  options.gyro_in_dps = true;
  const Recording r = Read(dir,
                           "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z\n"
                           "0,180,-90,0,1,2,3\n0.1,0,0,360,1,2,3\n",
                           options);
  ASSERT_EQ(r.gyro_radps.size(), 2u);
  EXPECT_NEAR(r.gyro_radps[0].x(), std::numbers::pi, 1e-15);
  EXPECT_NEAR(r.gyro_radps[0].y(), -std::numbers::pi / 2, 1e-15);
  EXPECT_NEAR(r.gyro_radps[1].z(), 2 * std::numbers::pi, 1e-15);
  EXPECT_EQ(r.accel[0], Eigen::Vector3d(1, 2, 3));
}

TEST(ReadLog, ColumnsMappingByNameAndIndex) {
  ScratchDir dir;
  LogOptions by_name;
  by_name.columns = "t=clock,ax=X,ay=Y,az=Z";
  const Recording a = Read(dir, "Z,Y,X,clock\n3,2,1,0.5\n6,5,4,0.6\n", by_name);
  EXPECT_EQ(a.time_s[0], 0.5);
  EXPECT_EQ(a.accel[0], Eigen::Vector3d(1, 2, 3));

  LogOptions by_index;
  by_index.columns = "t=3,ax=2,ay=1,az=0";
  const Recording b = Read(dir, "3 2 1 0.5\n6 5 4 0.6\n", by_index);
  EXPECT_EQ(b.time_s[1], 0.6);
  EXPECT_EQ(b.accel[1], Eigen::Vector3d(4, 5, 6));
}

TEST(ReadLog, PartialMappingCompletesFromHeader) {
  ScratchDir dir;
  LogOptions options;
  options.columns = "t=sensor_time";
  const Recording r = Read(dir, "sensor_time,ax,ay,az\n1.5,1,2,3\n2.5,4,5,6\n", options);
  EXPECT_EQ(r.time_s[1], 2.5);
  EXPECT_EQ(r.accel[1], Eigen::Vector3d(4, 5, 6));
}

TEST(ReadLog, SampleIndexColumnWithRate) {
  ScratchDir dir;
  LogOptions options;
  options.rate_hz = 102.4;
  const Recording r =
      Read(dir, "n_samples,acc_x,acc_y,acc_z\n0,1,2,3\n1,1,2,3\n2,1,2,3\n", options);
  ASSERT_EQ(r.size(), 3u);
  EXPECT_DOUBLE_EQ(r.time_s[2], 2.0 / 102.4);
}

TEST(ReadLog, SampleIndexWithoutRateSaysToGiveIt) {
  ScratchDir dir;
  const Error e = ReadFailure(dir, "n_samples,acc_x,acc_y,acc_z\n0,1,2,3\n1,1,2,3\n");
  EXPECT_THAT(e.what(), HasSubstr("n_samples"));
  EXPECT_EQ(e.kind(), ErrorKind::kTime);
  EXPECT_TRUE(Advises(e, Option::kLogRate));
}

TEST(ReadLog, ThreeColumnsWithRateHaveNoTimeColumn) {
  ScratchDir dir;
  LogOptions options;
  options.rate_hz = 50;
  const Recording r = Read(dir, "1 2 3\n4 5 6\n7 8 9\n", options);
  ASSERT_EQ(r.size(), 3u);
  EXPECT_DOUBLE_EQ(r.time_s[2], 0.04);
  EXPECT_EQ(r.accel[2], Eigen::Vector3d(7, 8, 9));
}

TEST(ReadLog, IntegerTimestampsUnitDetectedFromSpacing) {
  ScratchDir dir;
  struct Case {
    long long step;
    double seconds_per_unit;
    const char* unit;
  };
  // 100 Hz in ms, µs and ns; 1 kHz in µs.
  for (const Case& c : {Case{10, 1e-3, "ms"},
                        Case{10000, 1e-6, "us"},
                        Case{10000000, 1e-9, "ns"},
                        Case{1000, 1e-6, "us"}}) {
    std::string log = "t,ax,ay,az\n";
    const long long start = 1700000000LL;
    for (int i = 0; i < 20; ++i) log += std::to_string(start + i * c.step) + ",0,0,9.8\n";
    const Recording r = Read(dir, log);
    ASSERT_EQ(r.size(), 20u);
    // Seconds since 1.7e6 s (ms) carry a rounding of ~1e-10 s.
    EXPECT_NEAR(r.time_s[1] - r.time_s[0], c.step * c.seconds_per_unit, 1e-9) << c.unit;
    ASSERT_EQ(r.warnings.size(), 1u) << c.unit;
    EXPECT_THAT(r.warnings[0], HasSubstr(std::string("taken as ") + c.unit));
  }
}

TEST(ReadLog, GivenTimeUnitOverridesDetection) {
  ScratchDir dir;
  LogOptions options;
  options.time_unit = TimeUnit::kMilliseconds;
  const Recording r =
      Read(dir, "t,ax,ay,az\n1000,0,0,1\n2000,0,0,1\n3000,0,0,1\n", options);
  EXPECT_DOUBLE_EQ(r.time_s[1] - r.time_s[0], 1.0);
  EXPECT_TRUE(r.warnings.empty());
}

TEST(ReadLog, DuplicatedTimestampsDroppedAndReported) {
  ScratchDir dir;
  const Recording r =
      Read(dir, "t,ax,ay,az\n0.1,1,1,1\n0.2,2,2,2\n0.2,3,3,3\n0.3,4,4,4\n");
  ASSERT_EQ(r.size(), 3u);
  EXPECT_EQ(r.accel[1].x(), 2.0);  // the first of the duplicates is kept
  EXPECT_EQ(r.accel[2].x(), 4.0);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_THAT(r.warnings[0],
              AllOf(HasSubstr("1 row with a duplicated timestamp"), HasSubstr("line 4")));
}

TEST(ReadLog, GapsReported) {
  ScratchDir dir;
  std::string log = "t,ax,ay,az\n";
  for (int i = 0; i < 100; ++i) {
    log += std::to_string(i < 50 ? i * 0.01 : i * 0.01 + 2.0) + ",0,0,9.8\n";
  }
  const Recording r = Read(dir, log);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_THAT(r.warnings[0], AllOf(HasSubstr("1 gap"), HasSubstr("2.01 s")));
}

TEST(ReadLog, TimeGoingBackIsAnError) {
  ScratchDir dir;
  EXPECT_THAT(ReadError(dir, "t,ax,ay,az\n1,0,0,1\n2,0,0,1\n1.5,0,0,1\n3,0,0,1\n"),
              AllOf(HasSubstr("log.txt:4"), HasSubstr("time goes back")));
}

TEST(ReadLog, TimeGoingBackFromAWrappedCounterSaysSo) {
  // A 32-bit microsecond counter wraps at 4294.967296 s.
  ScratchDir dir;
  EXPECT_THAT(
      ReadError(dir,
                "t,ax,ay,az\n4294950000,0,0,1\n4294960000,0,0,1\n"
                "2704,0,0,1\n12704,0,0,1\n",
                WithTimeUnit(TimeUnit::kMicroseconds)),
      AllOf(HasSubstr("time goes back"), HasSubstr("32-bit counter that wrapped")));
  // Time that simply goes back gets no such guess.
  EXPECT_THAT(ReadError(dir, "t,ax,ay,az\n1,0,0,1\n2,0,0,1\n1.5,0,0,1\n"),
              ::testing::Not(HasSubstr("counter")));
}

TEST(ReadLog, QuotedFieldsAsSpreadsheetsWriteThem) {
  ScratchDir dir;
  const Recording r = Read(dir,
                           "\"time\",\"ax\",\"ay\",\"az\"\n"
                           "\"0.00\",\"0.1\",\"-0.2\",\"9.8\"\n"
                           "\"0.01\", \"0.11\" ,'-0.21',9.81\n");
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r.time_s[1], 0.01);
  EXPECT_EQ(r.accel[1], Eigen::Vector3d(0.11, -0.21, 9.81));
  // Without a header too, and an unclosed quote is a malformed field.
  EXPECT_EQ(Read(dir, "\"0\",\"1\",\"2\",\"3\"\n\"1\",\"1\",\"2\",\"3\"\n").size(), 2u);
  EXPECT_THAT(ReadError(dir, "t,ax,ay,az\n0,1,2,3\n1,\"1,2,3\n2,1,2,3\n"),
              AllOf(HasSubstr("log.txt:3"), HasSubstr("column 'ax'")));
}

TEST(ReadLog, CarriageReturnLineEndsAloneSayHowToConvert) {
  ScratchDir dir;
  EXPECT_THAT(ReadError(dir, "t,ax,ay,az\r0,0,0,1\r1,0,0,1\r"),
              AllOf(HasSubstr("carriage return alone"), HasSubstr("tr ")));
}

TEST(ReadLog, TruncatedLastLineDroppedWithWarning) {
  ScratchDir dir;
  const Recording r = Read(dir, "t,ax,ay,az\n0.1,1,2,3\n0.2,4,5,6\n0.3,7,8");
  ASSERT_EQ(r.size(), 2u);
  ASSERT_EQ(r.warnings.size(), 1u);
  EXPECT_THAT(r.warnings[0], AllOf(HasSubstr("log.txt:4"), HasSubstr("incomplete")));
}

TEST(ReadLog, TruncatedLineFollowedByBlankLinesIsStillTheLast) {
  ScratchDir dir;
  const Recording r = Read(dir, "t,ax,ay,az\n0.1,1,2,3\n0.2,4,5,6\n0.3,7,8.\n\n  \n");
  EXPECT_EQ(r.size(), 2u);
  EXPECT_EQ(r.warnings.size(), 1u);
}

TEST(ReadLog, MalformedLineInTheMiddleNamesLineAndExpectation) {
  ScratchDir dir;
  EXPECT_THAT(ReadError(dir, "t,ax,ay,az\n0.1,1,2,3\n0.2,4,5\n0.3,7,8,9\n"),
              AllOf(HasSubstr("log.txt:3"),
                    HasSubstr("expected at least 4 columns"),
                    HasSubstr("found 3")));
  EXPECT_THAT(ReadError(dir, "t,ax,ay,az\n0.1,1,2,3\n0.2,4,abc,5\n0.3,7,8,9\n"),
              AllOf(HasSubstr("log.txt:3"),
                    HasSubstr("'ay'"),
                    HasSubstr("'abc'"),
                    HasSubstr("expected a number")));
  EXPECT_THAT(ReadError(dir, "t,ax,ay,az\n0.1,1,2,3\n0.2,4,,5\n0.3,7,8,9\n"),
              AllOf(HasSubstr("log.txt:3"), HasSubstr("'ay'"), HasSubstr("empty")));
  EXPECT_THAT(ReadError(dir, "1 2 3 4\n5 6 7x 8\n9 10 11 12\n"),
              AllOf(HasSubstr("log.txt:2"), HasSubstr("'7x'")));
}

TEST(ReadLog, NonFiniteValuesRejectedWithLineAndColumn) {
  ScratchDir dir;
  for (const char* bad : {"nan", "NaN", "inf", "-inf", "Infinity"}) {
    const std::string log =
        std::string("t,ax,ay,az\n0.1,1,2,3\n0.2,4,") + bad + ",5\n0.3,7,8,9\n";
    EXPECT_THAT(ReadError(dir, log),
                AllOf(HasSubstr("log.txt:3"),
                      HasSubstr("non-finite"),
                      HasSubstr(bad),
                      HasSubstr("'ay' (index 2)")))
        << bad;
  }
}

TEST(ReadLog, MissingFileDirectoryAndEmptyFile) {
  ScratchDir dir;
  EXPECT_THROW(
      {
        try {
          ReadLog(dir.Path("nope.csv"), {});
        } catch (const Error& e) {
          EXPECT_THAT(e.what(), AllOf(HasSubstr("nope.csv"), HasSubstr("No such file")));
          throw;
        }
      },
      Error);
  EXPECT_THROW(
      {
        try {
          ReadLog(dir.path().string(), {});
        } catch (const Error& e) {
          EXPECT_THAT(e.what(), HasSubstr("is a directory"));
          throw;
        }
      },
      Error);
  EXPECT_THAT(ReadError(dir, ""), HasSubstr("is empty"));
  EXPECT_THAT(ReadError(dir, "# only\n# comments\n\n"), HasSubstr("only comments"));
}

TEST(ReadLog, HeaderOnlyProseAndBinaryJunk) {
  ScratchDir dir;
  EXPECT_THAT(ReadError(dir, "t,ax,ay,az\n"), HasSubstr("no data rows"));
  EXPECT_THAT(
      ReadError(dir, "Dear diary,\ntoday I held the sensor still.\nIt was fun.\n"),
      AllOf(HasSubstr("log.txt:2"), HasSubstr("expected a row of numbers")));
  const Error no_accel = ReadFailure(dir, "time,temperature,pressure\n1,20,1000\n");
  EXPECT_THAT(no_accel.what(), HasSubstr("names no accelerometer columns"));
  EXPECT_TRUE(Advises(no_accel, Option::kLogColumns));
  std::string junk = "\x89PNG\r\n\x1a\n";
  junk.push_back('\0');
  junk += "\x01\x02\x03";
  EXPECT_THAT(ReadError(dir, junk), HasSubstr("not a text log"));
}

TEST(ReadLog, TooFewColumns) {
  ScratchDir dir;
  EXPECT_THAT(
      ReadError(dir, "1 2 3\n4 5 6\n"),
      AllOf(HasSubstr("log.txt:1"), HasSubstr("too few columns"), HasSubstr("found 3")));
  EXPECT_THAT(ReadError(dir, "t,ax\n1,2\n"), HasSubstr("no column for ay"));
}

TEST(ReadLog, BadColumnsOption) {
  ScratchDir dir;
  LogOptions unknown_key;
  unknown_key.columns = "t=0,ax=1,ay=2,az=3,temp=4";
  EXPECT_THAT(ReadError(dir, "1 2 3 4 5\n", unknown_key),
              HasSubstr("unknown key 'temp'"));
  LogOptions unknown_name;
  unknown_name.columns = "ax=accel_north";
  EXPECT_THAT(ReadError(dir, "t,ax,ay,az\n1,2,3,4\n", unknown_name),
              AllOf(HasSubstr("no column 'accel_north'"), HasSubstr("t, ax, ay, az")));
  LogOptions names_without_header;
  names_without_header.columns = "t=time,ax=1,ay=2,az=3";
  EXPECT_THAT(ReadError(dir, "1 2 3 4\n", names_without_header), HasSubstr("no header"));
}

TEST(ReadLog, StandardInput) {
  ScratchDir dir;
  const std::string path = dir.Write("stdin.csv", "t,ax,ay,az\n0,1,2,3\n1,4,5,6\n");
  // Swap the process's stdin for the file, then put it back.
  const int saved = dup(STDIN_FILENO);
  ASSERT_NE(std::freopen(path.c_str(), "r", stdin), nullptr);
  Recording r;
  std::string error;
  try {
    r = ReadLog("-", {});
  } catch (const Error& e) {
    error = e.what();
  }
  dup2(saved, STDIN_FILENO);
  close(saved);
  EXPECT_EQ(error, "");
  ASSERT_EQ(r.size(), 2u);
  EXPECT_EQ(r.source, "<stdin>");
  EXPECT_EQ(r.accel[1], Eigen::Vector3d(4, 5, 6));
}

TEST(ReadLog, StandardInputLongerThanTheHeadGivesTheFilesRows) {
  ScratchDir dir;
  // 96 KB of comments before the header, then 1.5 MB of rows: from standard
  // input the head read for the layout is parsed a chunk at a time, from a
  // file the rows are read again after it.
  std::string log;
  for (int i = 0; i < 1600; ++i) log += fmt::format("# note {:04d} {:>48}\n", i, "x");
  log += "t,ax,ay,az\n";
  const int n = 50000;
  for (int i = 0; i < n; ++i) {
    log +=
        fmt::format("{:.3f},{:.5f},{:.5f},{:.5f}\n", 0.01 * i, 1e-5 * i, -2e-5 * i, 9.8);
  }
  const std::string path = dir.Write("long_stdin.csv", log);
  const Recording file = ReadLog(path, {});
  const int saved = dup(STDIN_FILENO);
  ASSERT_NE(std::freopen(path.c_str(), "r", stdin), nullptr);
  Recording piped;
  std::string error;
  try {
    piped = ReadLog("-", {});
  } catch (const Error& e) {
    error = e.what();
  }
  dup2(saved, STDIN_FILENO);
  close(saved);
  EXPECT_EQ(error, "");
  ASSERT_EQ(file.size(), static_cast<std::size_t>(n));
  EXPECT_TRUE(piped.time_s == file.time_s);
  EXPECT_TRUE(piped.accel == file.accel);
  EXPECT_DOUBLE_EQ(file.time_s.back(), 0.01 * (n - 1));
  EXPECT_DOUBLE_EQ(file.accel.back().x(), 1e-5 * (n - 1));
}

TEST(ReadLog, LongLogAcrossManyChunksMatchesItsRows) {
  ScratchDir dir;
  // ~3 MB: past the 1 MiB head and over many chunks, so that lines straddle
  // chunk boundaries.
  std::string log = "# long\ntime,ax,ay,az,extra\n";
  const int n = 60000;
  for (int i = 0; i < n; ++i) {
    log += std::to_string(i * 0.001) + "," + std::to_string(i % 97 * 0.125) + ",-" +
           std::to_string(i % 13) + ".5,9.80665,some-text\n";
  }
  std::vector<double> fractions;
  LogOptions options;
  options.progress = [&fractions](double f) { fractions.push_back(f); };
  const Recording r = Read(dir, log, options);
  ASSERT_EQ(r.size(), static_cast<std::size_t>(n));
  for (int i : {0, 1, 12345, 43690, n - 1}) {
    EXPECT_EQ(r.accel[i].x(), i % 97 * 0.125) << i;
    EXPECT_EQ(r.accel[i].y(), -(i % 13 + 0.5)) << i;
    EXPECT_EQ(r.accel[i].z(), 9.80665) << i;
  }
  ASSERT_FALSE(fractions.empty());
  EXPECT_EQ(fractions.back(), 1.0);
  EXPECT_LE(fractions.size(), 102u);
  EXPECT_TRUE(std::is_sorted(fractions.begin(), fractions.end()));
}

TEST(ReadLog, RealXsensRecordingInCounts) {
  LogOptions options;
  options.units = AccelUnits::kCounts;
  const Recording r = ReadLog(RealDataPath("xsens-multiposition/xsens_acc.mat"), options);
  // 512 s at 100 Hz.
  EXPECT_NEAR(static_cast<double>(r.size()), 51200.0, 200.0);
  EXPECT_EQ(r.time_s[0], 2.984e-02);
  EXPECT_EQ(r.accel[0], Eigen::Vector3d(33108, 33329, 36429));
  EXPECT_TRUE(r.warnings.empty()) << r.warnings.front();
}

TEST(ReadLog, RealFerrarisSessionWithSampleIndex) {
  LogOptions options;
  options.rate_hz = 102.4;
  const Recording r =
      ReadLog(RealDataPath("imucal-ferraris/example_ferraris_session.csv"), options);
  EXPECT_GT(r.size(), 10000u);
  EXPECT_EQ(r.accel[0].x(), 10.332114257812501);
  EXPECT_EQ(r.gyro_radps.size(), r.size());
  EXPECT_DOUBLE_EQ(r.time_s[3], 3 / 102.4);
}

TEST(ReadLog, RealRtklibImuLogWithUnixTimeAndExtraColumns) {
  LogOptions options;
  options.units = AccelUnits::kG;
  const Recording r = ReadLog(RealDataPath("rtklib-walk/imu_1730_sf.csv"), options);
  EXPECT_EQ(r.time_s[0], 1756402240.9610000);
  EXPECT_EQ(r.accel[0], Eigen::Vector3d(-0.0170050, -0.0070006, 1.0109805));
  // ~167 Hz over 134 s or more.
  EXPECT_GT(r.time_s.back() - r.time_s.front(), 130.0);
}

TEST(LogOptions, DefaultsAreValidAndBadFieldsNamed) {
  EXPECT_EQ(LogOptions{}.Validate(), "");
  LogOptions bad_rate;
  bad_rate.rate_hz = -1;
  EXPECT_THAT(bad_rate.Validate(), HasSubstr("rate_hz"));
  LogOptions index_without_rate;
  index_without_rate.time_unit = TimeUnit::kSampleIndex;
  EXPECT_THAT(index_without_rate.Validate(), HasSubstr("rate"));
  LogOptions bad_columns;
  bad_columns.columns = "t0,ax=1";
  EXPECT_THAT(bad_columns.Validate(), HasSubstr("columns"));
}

TEST(TimeUnit, ToStringAndParseRoundTrip) {
  for (TimeUnit u : {TimeUnit::kAuto,
                     TimeUnit::kSeconds,
                     TimeUnit::kMilliseconds,
                     TimeUnit::kMicroseconds,
                     TimeUnit::kNanoseconds,
                     TimeUnit::kSampleIndex}) {
    EXPECT_EQ(ParseTimeUnit(ToString(u)), u);
  }
  EXPECT_EQ(ParseTimeUnit("fortnights"), std::nullopt);
}

TEST(LogScanner, KeepsEveryLineAndTheSpansOfTheNumbers) {
  ScratchDir dir;
  const std::string path = dir.Write(
      "log.csv", "# c\r\nt, ax, ay, az, temp\r\n0.5, 1.25, -2, 3e1, 20\r\n\r\n");
  LogScanner scanner(path, {});
  std::vector<std::string> texts;
  LogLine line;
  while (scanner.Next(&line)) {
    texts.emplace_back(line.text);
    EXPECT_EQ(line.eol, "\r\n");
    if (line.is_data) {
      EXPECT_EQ(line.line_number, 3u);
      EXPECT_EQ(line.time_raw, 0.5);
      EXPECT_EQ(line.accel, Eigen::Vector3d(1.25, -2, 30));
      const auto [b, e] = line.accel_span[2];
      EXPECT_EQ(line.text.substr(b, e - b), "3e1");
      EXPECT_EQ(line.text.substr(line.accel_span[1].first,
                                 line.accel_span[1].second - line.accel_span[1].first),
                "-2");
    }
  }
  EXPECT_THAT(texts,
              ElementsAre("# c", "t, ax, ay, az, temp", "0.5, 1.25, -2, 3e1, 20", ""));
  EXPECT_EQ(scanner.layout().delimiter, ',');
  EXPECT_EQ(scanner.layout().header_line, 2u);
  EXPECT_EQ(scanner.layout().time_column, 0);
}

// Loggers as they are.
TEST(ReadLog, SerialBootTextBeforeTheHeaderIsSkippedWithAWarning) {
  ScratchDir dir;
  std::string log = std::string("\xf8\x00\xfe\x1c", 4) +
                    ",-0.0\r\nInitializing I2C devices...\r\n"
                    "MPU6050 connection successful\r\nmillis,ax,ay,az\r\n";
  for (int i = 0; i < 20; ++i) log += std::to_string(1000 + 10 * i) + ",0.1,0.2,9.8\r\n";
  log += "1200,0.1,x,9.8\r\n1210,0.1,0.2,9.8\r\n";
  const std::string path = dir.Write("serial.txt", log);
  try {
    ReadLog(path, {});
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    // Line numbers count the skipped lines: the bad row is line 25.
    EXPECT_THAT(e.what(), HasSubstr("serial.txt:25: "));
  }
  const std::string good = log.substr(0, log.find("1200,"));
  const Recording r = ReadLog(dir.Write("good.txt", good), {});
  ASSERT_EQ(r.size(), 20u);
  EXPECT_NEAR(r.time_s[1] - r.time_s[0], 0.01, 1e-12);  // `millis`: ms from the name
  EXPECT_THAT(r.warnings,
              ::testing::Contains(
                  HasSubstr("skipped 3 lines before the header (serial boot text or a "
                            "title); the header starts on line 4")));
}

TEST(ReadLog, TimeUnitFromTheColumnName) {
  ScratchDir dir;
  for (const auto& [name, step] : {std::pair{"timestamp_ms", 1e-3},
                                   std::pair{"time_us", 1e-6},
                                   std::pair{"\"Time (s)\"", 1.0},
                                   std::pair{"micros", 1e-6}}) {
    std::string log = std::string(name) + ",ax,ay,az\n";
    for (int i = 0; i < 10; ++i) log += std::to_string(5 * i) + ",0,0,9.8\n";
    const Recording r = Read(dir, log);
    EXPECT_NEAR(r.time_s[1] - r.time_s[0], 5 * step, 1e-12) << name;
  }
}

TEST(ReadLog, AnIndexSteppingByOneAsksForTheRate) {
  ScratchDir dir;
  std::string log;
  for (int i = 0; i < 20; ++i) log += std::to_string(i) + " 0.01 0.02 1.0\n";
  EXPECT_THAT(
      ReadError(dir, log),
      HasSubstr("steps by exactly 1 on every row: it is a sample index, not a time"));
  LogOptions with_rate;
  with_rate.rate_hz = 100.0;
  EXPECT_NEAR(Read(dir, log, with_rate).time_s[1], 0.01, 1e-12);
}

TEST(ReadLog, ImpossibleReadingIsAnErrorNamingTheLine) {
  ScratchDir dir;
  EXPECT_THAT(
      ReadError(dir, "t,ax,ay,az\n0,0,0,9.8\n0.01,1e20,0,9.8\n0.02,0,0,9.8\n"),
      HasSubstr("log.txt:3: reading '1e20' in column 'ax' (index 1) is beyond any "
                "accelerometer's range"));
  // 30,000 g read as g is impossible; as counts it is a reading.
  const std::string counts = "t,ax,ay,az\n0,0,0,30000\n0.01,0,0,30001\n";
  EXPECT_THAT(ReadError(dir, counts, WithUnits(AccelUnits::kG)), HasSubstr("beyond"));
  EXPECT_EQ(Read(dir, counts, WithUnits(AccelUnits::kCounts)).size(), 2u);
  EXPECT_THAT(ReadError(dir, "t,ax,ay,az\n1e300,0,0,9.8\n2e300,0,0,9.8\n"),
              HasSubstr("a time of 1e+300 s is beyond any logger's clock"));
}

}  // namespace
}  // namespace mpcal
