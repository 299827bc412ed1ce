// LiveLogParser against ReadLog, the reader it must agree with: the same
// text fed in any pieces gives ReadLog's rows, and the session text it hands
// over reads back (with ReadLog) to the same rows.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <numbers>
#include <string>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "../../fuzz/live_log_input.h"
#include "mpcal/error.h"
#include "mpcal/live_source.h"
#include "mpcal/log_reader.h"
#include "test_util.h"

namespace mpcal {
namespace {

using ::testing::Contains;
using ::testing::HasSubstr;
using testing::ScratchDir;
using ::testing::StartsWith;

// A still sensor's log: t in s at 100 Hz, accel near (0, 0, 9.81) with a
// little noise, the gyroscope near zero; every value distinct.
std::string Lines(int rows, bool gyro, int first = 0) {
  std::string text;
  for (int i = first; i < first + rows; ++i) {
    const double w = std::sin(0.37 * i);
    text += fmt::format(
        "{:.2f},{:.5f},{:.5f},{:.5f}", 0.01 * i, 0.01 * w, -0.02 * w, 9.81 + 0.003 * w);
    if (gyro)
      text += fmt::format(",{:.6f},{:.6f},{:.6f}", 0.001 * w, 0.002 * w, -0.001 * w);
    text += "\n";
  }
  return text;
}

// Feeds `text` in pieces cut at `cuts` (increasing byte offsets), then ends.
Recording FeedInPieces(const std::string& text,
                       const std::vector<std::size_t>& cuts,
                       const LogOptions& options = {},
                       std::string* session = nullptr) {
  LiveLogParser parser(options, "live");
  Recording rows;
  std::size_t from = 0;
  for (const std::size_t cut : cuts) {
    parser.Feed(std::string_view(text).substr(from, cut - from), &rows);
    if (session) *session += parser.TakeSessionText();
    from = cut;
  }
  parser.Feed(std::string_view(text).substr(from), &rows);
  parser.Finish(&rows);
  if (session) *session += parser.TakeSessionText();
  return rows;
}

void ExpectSameRows(const Recording& a, const Recording& b) {
  ASSERT_EQ(a.size(), b.size());
  ASSERT_EQ(a.gyro_radps.size(), b.gyro_radps.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a.time_s[i], b.time_s[i]) << "row " << i;
    ASSERT_EQ(a.accel[i], b.accel[i]) << "row " << i;
    if (!a.gyro_radps.empty()) {
      ASSERT_EQ(a.gyro_radps[i], b.gyro_radps[i]) << "row " << i;
    }
  }
  EXPECT_EQ(a.units, b.units);
  EXPECT_EQ(a.gyro_units, b.gyro_units);
}

TEST(LiveLogParser, CutAtEveryByteGivesTheRowsReadLogGives) {
  ScratchDir dir;
  const std::string text = "# logger v2\nt,ax,ay,az,gx,gy,gz\n" + Lines(80, true);
  const Recording expected = ReadLog(dir.Write("log.csv", text), {});
  ASSERT_EQ(expected.size(), 80u);
  for (std::size_t cut = 0; cut <= text.size(); ++cut) {
    ExpectSameRows(FeedInPieces(text, {cut}), expected);
    if (HasFatalFailure()) FAIL() << "cut at byte " << cut;
  }
  // Byte by byte, and in three pieces at odd places.
  std::vector<std::size_t> every;
  for (std::size_t i = 1; i < text.size(); ++i) every.push_back(i);
  ExpectSameRows(FeedInPieces(text, every), expected);
  ExpectSameRows(FeedInPieces(text, {7, 1000, 1001}), expected);
}

TEST(LiveLogParser, SessionTextReadsBackToTheSameRows) {
  ScratchDir dir;
  const std::string text = "t,ax,ay,az,gx,gy,gz\r\n" + Lines(100, true);
  std::string session;
  const Recording rows = FeedInPieces(text, {5, 300, 2000}, {}, &session);
  EXPECT_EQ(session, text);  // a stream with a header: exactly as received
  ExpectSameRows(ReadLog(dir.Write("session.csv", session), {}), rows);
}

TEST(LiveLogParser, LayoutIsFoundFromTheFirstLinesWithoutWaitingForTheEnd) {
  LiveLogParser parser({}, "live");
  Recording rows;
  parser.Feed("t,ax,ay,az\n" + Lines(20, false), &rows);
  EXPECT_FALSE(parser.layout_known());  // 20 rows: not yet
  EXPECT_TRUE(rows.empty());
  parser.Feed(Lines(40, false, 20), &rows);
  ASSERT_TRUE(parser.layout_known());
  EXPECT_EQ(parser.layout().header_line, 1u);
  EXPECT_EQ(parser.layout().accel_columns[2], 3);
  EXPECT_EQ(rows.size(), 60u);
  EXPECT_NEAR(rows.time_s.back(), 0.59, 1e-12);
  // An incomplete line waits for its end.
  rows.time_s.clear();
  rows.accel.clear();
  const std::string next = Lines(1, false, 60);
  parser.Feed(next.substr(0, 9), &rows);
  EXPECT_TRUE(rows.empty());
  parser.Feed(next.substr(9), &rows);
  ASSERT_EQ(rows.size(), 1u);
  EXPECT_NEAR(rows.time_s[0], 0.60, 1e-12);
}

TEST(LiveLogParser, BootTextAndACutFirstLineAreSkippedAndCountedAsInAFile) {
  ScratchDir dir;
  // A serial port opened mid-line, the board reset by the opening: the
  // tail of a line (5 of 7 fields), boot text, then whole lines.
  const std::string text =
      "0.00100,0.00200,-0.00100,0.5,0.2\nInitializing I2C...\r\n"
      "MPU6050 connection successful\r\n" +
      Lines(70, true, 3);
  std::string session;
  const Recording rows = FeedInPieces(text, {2, 30, 95}, {}, &session);
  const Recording file = ReadLog(dir.Write("serial.txt", text), {});
  ExpectSameRows(rows, file);
  ASSERT_EQ(rows.size(), 70u);
  EXPECT_NEAR(rows.time_s[0], 0.03, 1e-12);
  LiveLogParser parser({}, "serial");
  Recording r;
  parser.Feed(text, &r);
  EXPECT_EQ(parser.skipped_lines(), 3u);
  EXPECT_THAT(parser.warnings(), Contains(HasSubstr("skipped 3 lines before the data")));
  EXPECT_THAT(file.warnings, Contains(HasSubstr("skipped 3 lines before the data")));
  // Without the boot text: the cut line alone is skipped.
  const std::string cut_only = "0.5,0.2\n" + Lines(70, true, 3);
  const Recording after_cut = FeedInPieces(cut_only, {3});
  ExpectSameRows(after_cut, ReadLog(dir.Write("cut.txt", cut_only), {}));
  ASSERT_EQ(after_cut.size(), 70u);  // no header: t, ax, ay, az as ReadLog maps them
  // The session holds no boot text: a header of the layout's names, then
  // the lines as received.
  // (No header: t, ax, ay, az as ReadLog maps them; the others named.)
  EXPECT_THAT(session, StartsWith("t,ax,ay,az,c4,c5,c6\n0.03,"));
  ExpectSameRows(ReadLog(dir.Write("session.csv", session), {}), rows);
}

TEST(LiveLogParser, AStreamWithoutHeaderGetsOneInItsSession) {
  ScratchDir dir;
  const std::string text = Lines(60, false);
  std::string session;
  const Recording rows = FeedInPieces(text, {100}, {}, &session);
  EXPECT_EQ(session, "t,ax,ay,az\n" + text);
  ExpectSameRows(ReadLog(dir.Write("session.csv", session), {}), rows);
  // Blank-separated, with an extra column: the same separator, a name for it.
  std::string blanks;
  for (int i = 0; i < 60; ++i)
    blanks += fmt::format("{} 0.1 0.2 9.8 {}\n", 10 * i, 25 + i);
  LogOptions options;
  session.clear();
  const Recording ms = FeedInPieces(blanks, {}, options, &session);
  EXPECT_THAT(session, StartsWith("t ax ay az c4\n0 0.1"));
  EXPECT_NEAR(ms.time_s[1] - ms.time_s[0], 0.010, 1e-12);  // integer ms, as ReadLog finds
  ExpectSameRows(ReadLog(dir.Write("blanks.txt", session), options), ms);
}

TEST(LiveLogParser, UnitsAsReadLogKeepsAndConvertsThem) {
  ScratchDir dir;
  std::string text = "time_ms,acc_x,acc_y,acc_z,gyr_x,gyr_y,gyr_z\n";
  for (int i = 0; i < 60; ++i) {
    text += fmt::format("{},0.01,-0.02,1.001,90,0,-45\n", 1000 + 5 * i);
  }
  LogOptions options;
  options.units = AccelUnits::kG;
  options.gyro_in_dps = true;
  const Recording rows = FeedInPieces(text, {333}, options);
  ExpectSameRows(rows, ReadLog(dir.Write("g.csv", text), options));
  EXPECT_EQ(rows.units, AccelUnits::kG);
  EXPECT_EQ(rows.gyro_log_units, GyroUnits::kDps);
  EXPECT_DOUBLE_EQ(rows.accel[0].z(), 1.001);  // in g, as the log has it
  EXPECT_NEAR(rows.gyro_radps[0].x(), std::numbers::pi / 2, 1e-12);
  EXPECT_NEAR(rows.gyro_radps[0].z(), -std::numbers::pi / 4, 1e-12);
  EXPECT_NEAR(rows.time_s[1] - rows.time_s[0], 0.005, 1e-12);
  // 9.81 read as g is a reading; 20000 g is one no accelerometer gives.
  LiveLogParser parser(options, "live");
  Recording r;
  parser.Feed("t,ax,ay,az\n" + Lines(60, false), &r);
  EXPECT_EQ(r.size(), 60u);
  // Refused once a line follows it (alone at the end, a cut-off last line).
  EXPECT_THAT([&] { parser.Feed("0.60,0,0,20000\n0.61,0,0,1\n", &r); },
              ::testing::ThrowsMessage<Error>(
                  HasSubstr("live:62: reading '20000' in column 'az' (index 3) is beyond "
                            "any accelerometer's range")));
}

TEST(LiveLogParser, AMalformedLineWithDataAfterItIsAnErrorAndStaysOutOfTheSession) {
  ScratchDir dir;
  const std::string text =
      "t,ax,ay,az\n" + Lines(60, false) + "0.60,0.1,x,9.8\n" + Lines(5, false, 61);
  LiveLogParser parser({}, "live");
  Recording rows;
  std::string session;
  try {
    parser.Feed(text, &rows);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("live:62: expected a number in column 'ay'"));
  }
  session = parser.TakeSessionText();
  EXPECT_EQ(rows.size(), 60u);  // the rows before the error were handed over
  EXPECT_EQ(session, "t,ax,ay,az\n" + Lines(60, false) + "0.60,0.1,x,9.8\n");
  // The session file is readable: its malformed last line is dropped.
  const Recording back = ReadLog(dir.Write("session.csv", session), {});
  ExpectSameRows(back, rows);
  EXPECT_THAT(back.warnings, Contains(HasSubstr("last line is incomplete")));
}

TEST(LiveLogParser, TimeGoingBackIsAnErrorAfterTheRowsBeforeIt) {
  LiveLogParser parser({}, "live");
  Recording rows;
  const std::string text = "t,ax,ay,az\n" + Lines(60, false) + "0.30,0,0,9.8\n";
  EXPECT_THAT([&] { parser.Feed(text, &rows); },
              ::testing::ThrowsMessage<Error>(HasSubstr("live:62: time goes back")));
  EXPECT_EQ(rows.size(), 60u);
  EXPECT_EQ(parser.TakeSessionText(), "t,ax,ay,az\n" + Lines(60, false));
}

TEST(LiveLogParser, AStreamThatIsNotImuLinesIsRefusedWithinBoundedBytes) {
  LiveLogParser parser({}, "live");
  Recording rows;
  const std::string prose = "The quick brown fox jumps over the lazy dog, again.\n";
  std::size_t fed = 0;
  try {
    while (fed < (std::size_t{1} << 20)) {
      parser.Feed(prose, &rows);
      fed += prose.size();
    }
    ADD_FAILURE() << "no error after " << fed << " bytes";
  } catch (const Error& e) {
    EXPECT_LE(fed, std::size_t{1} << 16);
    EXPECT_THAT(e.what(), HasSubstr("live"));
  }
}

TEST(LiveLogParser, AShortStreamIsParsedAtItsEnd) {
  ScratchDir dir;
  const std::string text = "t,ax,ay,az\n0,0,0,9.8\n0.01,0,0,9.81\n0.02,0,0,9.79";
  std::string session;
  const Recording rows = FeedInPieces(text, {12}, {}, &session);
  ASSERT_EQ(rows.size(), 3u);
  EXPECT_EQ(session, text);
  ExpectSameRows(ReadLog(dir.Write("short.csv", text), {}), rows);
  LiveLogParser empty({}, "live");
  Recording none;
  EXPECT_THAT([&] { empty.Finish(&none); },
              ::testing::ThrowsMessage<Error>(HasSubstr("'live' is empty")));
}

// The fuzz target's seed corpus (tests/fuzz/live_log/) replayed: every
// stream parses the same in any pieces (the sanitizer build runs this too).
TEST(LiveLogParser, TheFuzzCorpusParsesTheSameInAnyPieces) {
  std::vector<std::filesystem::path> files;
  for (const auto& e :
       std::filesystem::directory_iterator(testing::TestDataPath("../fuzz/live_log"))) {
    if (e.is_regular_file()) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  ASSERT_GE(files.size(), 5u);
  for (const auto& file : files) {
    const std::string bytes = testing::ReadFile(file.string());
    EXPECT_EQ(fuzz::CheckLiveLogInput(reinterpret_cast<const std::uint8_t*>(bytes.data()),
                                      bytes.size()),
              "")
        << file.filename();
  }
}

}  // namespace
}  // namespace mpcal
