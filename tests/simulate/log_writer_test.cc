// Tests of the CSV log writer: format, round trip through ReadLog, refusal
// of inconsistent or non-finite recordings with no file left behind.
#include "mpcal/log_writer.h"

#include <cmath>
#include <filesystem>
#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mpcal/error.h"
#include "mpcal/log_reader.h"
#include "mpcal/simulate.h"
#include "test_util.h"

namespace mpcal {
namespace {

using ::testing::HasSubstr;
using ::testing::StartsWith;

SimulatedSession Session(AccelUnits units, bool gyro = false) {
  SimulateStaticOptions options;
  options.device = FindPreset("inertiacube3");
  options.positions = 4;
  options.dwell_s = 1.0;
  options.turn_s = 0.5;
  options.initial_rest_s = 0.5;
  options.units = units;
  options.gyro = gyro;
  return SimulateStatic(options);
}

TEST(LogWriter, WritesHeaderAndRowsInTheRecordingsUnits) {
  Recording r;
  r.time_s = {0.0, 0.01};
  r.accel = {{1.5, -2.25, 9.80665}, {0.1, 0.2, 0.3}};
  std::ostringstream out;
  WriteRecordingCsv(out, r);
  EXPECT_EQ(out.str(), "t,ax,ay,az\n0,1.5,-2.25,9.80665\n0.01,0.1,0.2,0.3\n");

  r.units = AccelUnits::kCounts;
  r.accel = {{32768, -5, 0}, {1, 2, 3.5}};
  r.gyro_radps = {{0.5, 0, -0.5}, {0, 0, 0}};
  std::ostringstream counts;
  WriteRecordingCsv(counts, r);
  EXPECT_EQ(counts.str(),
            "t,ax,ay,az,gx,gy,gz\n0,32768,-5,0,0.5,0,-0.5\n0.01,1,2,3.5,0,0,0\n");
}

TEST(LogWriter, SignificantDigitsLimitTheReadingsNotTheTime) {
  Recording r;
  r.time_s = {1.0 / 3.0};
  r.accel = {{std::acos(-1.0), 1.0 / 7.0, -2.0 / 3.0}};
  LogWriteOptions options;
  options.significant_digits = 4;
  std::ostringstream out;
  WriteRecordingCsv(out, r, options);
  EXPECT_EQ(out.str(), "t,ax,ay,az\n0.3333333333333333,3.142,0.1429,-0.6667\n");
}

void ExpectRoundTrip(AccelUnits units, bool gyro, int digits) {
  SCOPED_TRACE(std::string(ToString(units)) + (gyro ? " with gyro" : ""));
  const testing::ScratchDir dir;
  const SimulatedSession s = Session(units, gyro);
  LogWriteOptions write;
  write.significant_digits = digits;
  const std::string path = dir.Path("session.csv");
  WriteRecordingFile(path, s.recording, write);
  LogOptions read;
  read.units = units;
  const Recording back = ReadLog(path, read);
  ASSERT_EQ(back.size(), s.recording.size());
  ASSERT_EQ(back.gyro_radps.size(), s.recording.gyro_radps.size());
  // Relative error of a value printed with d significant digits: 5·10^-d.
  const double relative = digits == 0 ? 0.0 : 5 * std::pow(10.0, -digits);
  for (std::size_t i = 0; i < back.size(); ++i) {
    ASSERT_EQ(back.time_s[i], s.recording.time_s[i]) << "row " << i;
    for (int k = 0; k < 3; ++k) {
      const double a = s.recording.accel[i][k];
      ASSERT_NEAR(back.accel[i][k], a, relative * std::abs(a))
          << "row " << i << " axis " << k;
      if (gyro) {
        const double g = s.recording.gyro_radps[i][k];
        ASSERT_NEAR(back.gyro_radps[i][k], g, relative * std::abs(g)) << "row " << i;
      }
    }
  }
}

TEST(LogWriter, ReadLogReadsBackWhatItWrote) {
  ExpectRoundTrip(AccelUnits::kMps2, false, 9);
  ExpectRoundTrip(AccelUnits::kG, true, 9);
  ExpectRoundTrip(AccelUnits::kCounts, false, 9);
  ExpectRoundTrip(AccelUnits::kMps2, true, 0);  // exact
}

TEST(LogWriter, NonFiniteValueIsRefusedAndNoFileIsLeft) {
  const testing::ScratchDir dir;
  SimulatedSession s = Session(AccelUnits::kMps2);
  s.recording.accel[200].y() = std::nan("");
  const std::string path = dir.Path("bad.csv");
  try {
    WriteRecordingFile(path, s.recording);
    FAIL() << "no exception";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("sample 200"));
  }
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()),
                          std::filesystem::directory_iterator()),
            0);
}

TEST(LogWriter, InconsistentColumnsAndBadOptionsAreRefused) {
  Recording r;
  r.time_s = {0.0, 1.0};
  r.accel = {{0, 0, 1}};
  std::ostringstream out;
  EXPECT_THROW(WriteRecordingCsv(out, r), Error);
  r.accel.push_back({0, 0, 1});
  r.gyro_radps = {{0, 0, 0}};
  EXPECT_THROW(WriteRecordingCsv(out, r), Error);
  r.gyro_radps.clear();
  LogWriteOptions bad;
  bad.significant_digits = 30;
  EXPECT_THAT(bad.Validate(), HasSubstr("significant_digits"));
  EXPECT_THROW(WriteRecordingCsv(out, r, bad), Error);
  EXPECT_EQ(LogWriteOptions{}.Validate(), "");
}

TEST(LogWriter, EmptyRecordingIsJustTheHeader) {
  std::ostringstream out;
  WriteRecordingCsv(out, Recording{});
  EXPECT_THAT(out.str(), StartsWith("t,ax,ay,az\n"));
  EXPECT_EQ(out.str(), "t,ax,ay,az\n");
}

TEST(LogWriter, MissingDirectoryThrows) {
  const testing::ScratchDir dir;
  EXPECT_THROW(WriteRecordingFile(dir.Path("no/such/dir/x.csv"),
                                  Session(AccelUnits::kG).recording),
               Error);
}

}  // namespace
}  // namespace mpcal
