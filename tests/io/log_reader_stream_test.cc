// ReadLogRows: the same rows, warnings and errors as ReadLog, handed over
// chunk by chunk.
#include <algorithm>
#include <cstddef>
#include <numbers>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mpcal/error.h"
#include "mpcal/log_reader.h"
#include "test_util.h"

namespace mpcal {
namespace {

using mpcal::testing::ScratchDir;
using ::testing::AllOf;
using ::testing::ElementsAre;
using ::testing::HasSubstr;

// A chunk is 64 KiB of text (the layout's first mebibyte too is parsed in
// chunks of that size): a piece never holds more rows than fit in one at the
// log's shortest line, so the reader's buffers stay small beside the rows.
constexpr std::size_t kChunkBytes = std::size_t{1} << 16;

// The pieces ReadLogRows hands over, concatenated, with what each call saw.
struct Streamed {
  Recording rows;
  LogStreamSummary summary;
  std::size_t calls = 0;
  std::size_t largest_piece = 0;
  bool increasing = true;       // time strictly increasing within and across pieces
  bool consistent = true;       // vector sizes agree in every piece
  bool described_alike = true;  // units, gyro_units, source as ReadLog's
};

// Streams `path`, checking every piece against `whole` (ReadLog's result)
// for what must hold in each call.
Streamed Stream(const std::string& path,
                const LogOptions& options,
                const Recording& whole) {
  Streamed s;
  s.summary = ReadLogRows(path, options, [&s, &whole](const Recording& piece) {
    ++s.calls;
    s.largest_piece = std::max(s.largest_piece, piece.size());
    s.consistent = s.consistent && piece.accel.size() == piece.size() &&
                   (piece.gyro_radps.empty() || piece.gyro_radps.size() == piece.size());
    s.described_alike = s.described_alike && piece.units == whole.units &&
                        piece.gyro_units == whole.gyro_units &&
                        piece.source == whole.source && piece.warnings.empty();
    for (const double t : piece.time_s) {
      if (!s.rows.time_s.empty() && !(t > s.rows.time_s.back())) s.increasing = false;
      s.rows.time_s.push_back(t);
    }
    s.rows.accel.insert(s.rows.accel.end(), piece.accel.begin(), piece.accel.end());
    s.rows.gyro_radps.insert(
        s.rows.gyro_radps.end(), piece.gyro_radps.begin(), piece.gyro_radps.end());
  });
  return s;
}

// Reads `content` both ways and checks that they agree; returns the stream.
Streamed ExpectSameAsReadLog(const ScratchDir& dir,
                             const std::string& content,
                             const LogOptions& options = {}) {
  const std::string path = dir.Write("log.txt", content);
  const Recording whole = ReadLog(path, options);
  Streamed s = Stream(path, options, whole);
  EXPECT_TRUE(s.rows.time_s == whole.time_s);
  EXPECT_TRUE(s.rows.accel == whole.accel);
  EXPECT_TRUE(s.rows.gyro_radps == whole.gyro_radps);
  EXPECT_EQ(s.summary.warnings, whole.warnings);
  EXPECT_EQ(s.summary.source, whole.source);
  EXPECT_EQ(s.summary.rows, whole.size());
  EXPECT_EQ(s.summary.first_time_s, whole.time_s.front());
  EXPECT_EQ(s.summary.last_time_s, whole.time_s.back());
  EXPECT_EQ(s.summary.has_gyro, !whole.gyro_radps.empty());
  EXPECT_TRUE(s.increasing);
  EXPECT_TRUE(s.consistent);
  EXPECT_TRUE(s.described_alike);
  EXPECT_GE(s.calls, 1u);
  return s;
}

// The mpcal::Error's message, or "" with a failure when none is thrown.
template <typename Read>
std::string MessageOf(Read read) {
  try {
    read();
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error";
  return "";
}

// A 400 Hz log with gyroscope, `rows` long (about 75 bytes a row), with
// rows that repeat the time before (`duplicate_every`) and a gap of 0.5 s
// every `gap_every` rows (0: none).
std::string LongLog(int rows, int duplicate_every, int gap_every) {
  std::string log = "time,acc_x,acc_y,acc_z,gyr_x,gyr_y,gyr_z\n";
  double t = 1000.0;
  for (int i = 0; i < rows; ++i) {
    const bool duplicate = duplicate_every > 0 && i > 0 && i % duplicate_every == 0;
    if (!duplicate && i > 0) t += gap_every > 0 && i % gap_every == 0 ? 0.5 : 0.0025;
    log += fmt::format("{:.4f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f},{:.6f}\n",
                       t,
                       0.01 * (i % 97),
                       -0.02 * (i % 89),
                       9.81 + 1e-4 * (i % 13),
                       1e-3 * (i % 7),
                       -1e-3 * (i % 11),
                       2e-3 * (i % 5));
  }
  return log;
}

TEST(ReadLogRows, HeaderAndGyroscopeInDegreesPerSecond) {
  ScratchDir dir;
  LogOptions options;
  options.gyro_in_dps = true;
  const Streamed s = ExpectSameAsReadLog(dir,
                                         "t,gyr_x,gyr_y,gyr_z,acc_x,acc_y,acc_z\n"
                                         "0,180,-90,0,1,2,3\n0.1,0,0,360,1,2,3\n",
                                         options);
  EXPECT_EQ(s.calls, 1u);
  ASSERT_EQ(s.rows.gyro_radps.size(), 2u);
  EXPECT_NEAR(s.rows.gyro_radps[1].z(), 2 * std::numbers::pi, 1e-15);
}

TEST(ReadLogRows, NoTimeColumnNumbersRowsAcrossChunks) {
  ScratchDir dir;
  std::string log;
  for (int i = 0; i < 500000; ++i) log += fmt::format("{} {} {}\n", i % 10, -i % 7, 9.8);
  LogOptions options;
  options.rate_hz = 50;
  const Streamed s = ExpectSameAsReadLog(dir, log, options);
  EXPECT_GE(s.calls, 3u);
  ASSERT_EQ(s.rows.size(), 500000u);
  EXPECT_DOUBLE_EQ(s.rows.time_s.back(), 499999 / 50.0);
}

TEST(ReadLogRows, DuplicatedTimestampsDroppedAsReadLogDoes) {
  ScratchDir dir;
  const Streamed s = ExpectSameAsReadLog(
      dir, "t,ax,ay,az\n0.1,1,1,1\n0.2,2,2,2\n0.2,3,3,3\n0.3,4,4,4\n");
  EXPECT_THAT(s.rows.time_s, ElementsAre(0.1, 0.2, 0.3));
  ASSERT_EQ(s.summary.warnings.size(), 1u);
  EXPECT_THAT(s.summary.warnings[0], HasSubstr("1 row with a duplicated timestamp"));
}

TEST(ReadLogRows, CutOffLastLineDroppedWithTheSameWarning) {
  ScratchDir dir;
  const Streamed s =
      ExpectSameAsReadLog(dir, LongLog(30000, 0, 0) + "1075.0000,0.1,0.2\n\n\n");
  ASSERT_EQ(s.summary.warnings.size(), 1u);
  EXPECT_THAT(s.summary.warnings[0],
              AllOf(HasSubstr("log.txt:30002"), HasSubstr("incomplete")));
}

TEST(ReadLogRows, GapsReportedAsReadLogDoes) {
  ScratchDir dir;
  std::string log = "t,ax,ay,az\n";
  for (int i = 0; i < 100; ++i) {
    log += std::to_string(i < 50 ? i * 0.01 : i * 0.01 + 2.0) + ",0,0,9.8\n";
  }
  const Streamed s = ExpectSameAsReadLog(dir, log);
  ASSERT_EQ(s.summary.warnings.size(), 1u);
  EXPECT_THAT(s.summary.warnings[0], AllOf(HasSubstr("1 gap"), HasSubstr("2.01 s")));
}

TEST(ReadLogRows, IntegerTimeUnitWarningKept) {
  ScratchDir dir;
  std::string log = "t,ax,ay,az\n";
  for (int i = 0; i < 1000; ++i) log += fmt::format("{},0,0,9.8\n", 5000000 + 2500 * i);
  const Streamed s = ExpectSameAsReadLog(dir, log);
  EXPECT_FALSE(s.summary.warnings.empty());
  EXPECT_DOUBLE_EQ(s.summary.last_time_s - s.summary.first_time_s, 999 * 0.0025);
}

TEST(ReadLogRows, LongLogComesInManyBoundedPieces) {
  ScratchDir dir;
  // About 9 MiB: duplicates and gaps fall in every chunk and across their
  // boundaries; the typical step is known only after 10,000 steps.
  const int rows = 125000;
  const Streamed s = ExpectSameAsReadLog(dir, LongLog(rows, 997, 4001));
  EXPECT_GE(s.calls, 8u);
  constexpr std::size_t kShortestLineBytes = 60;
  EXPECT_LE(s.largest_piece, kChunkBytes / kShortestLineBytes);
  const std::size_t duplicates = (rows - 1) / 997;
  EXPECT_EQ(s.summary.rows, rows - duplicates);
  ASSERT_EQ(s.summary.warnings.size(), 2u);
  EXPECT_THAT(s.summary.warnings[0],
              HasSubstr(fmt::format("{} rows with a duplicated timestamp", duplicates)));
  // A gap step at row i is not also a duplicate's (none shares a multiple).
  EXPECT_THAT(s.summary.warnings[1],
              AllOf(HasSubstr(fmt::format("{} gaps", (rows - 1) / 4001)),
                    HasSubstr("(0.0025 s)"),
                    HasSubstr("largest is 0.5 s")));
}

TEST(ReadLogRows, FirstMebibyteComesInBoundedPiecesToo) {
  ScratchDir dir;
  // 0.9 MB: the whole log lies in the first mebibyte read to find its layout.
  const Streamed s = ExpectSameAsReadLog(dir, LongLog(12000, 0, 0));
  constexpr std::size_t kShortestLineBytes = 60;
  EXPECT_LE(s.largest_piece, kChunkBytes / kShortestLineBytes);
  EXPECT_GE(s.calls, 12000 * kShortestLineBytes / kChunkBytes);
}

TEST(ReadLogRows, HeaderAfterMoreThanAChunkOfCommentsIsStillTheHeader) {
  ScratchDir dir;
  // 96 KB of comments: the header lies beyond the first chunk's size.
  std::string log;
  for (int i = 0; i < 1600; ++i) log += fmt::format("# note {:04d} {:>48}\n", i, "x");
  log += LongLog(3000, 0, 0);
  const Streamed s = ExpectSameAsReadLog(dir, log);
  EXPECT_EQ(s.summary.rows, 3000u);
  EXPECT_TRUE(s.summary.has_gyro);
  EXPECT_DOUBLE_EQ(s.rows.time_s.front(), 1000.0);
  EXPECT_DOUBLE_EQ(s.rows.accel.back().z(), 9.81 + 1e-4 * (2999 % 13));
}

TEST(ReadLogRows, TimeGoingBackInALaterChunkThrowsAfterTheRowsBefore) {
  ScratchDir dir;
  const int bad_row = 90000;  // well past the first chunks
  std::string log = LongLog(bad_row, 0, 0);
  log += "1000.1000,0,0,9.8,0,0,0\n1300,0,0,9.8,0,0,0\n";
  const std::string path = dir.Write("log.txt", log);
  const std::string expected = MessageOf([&] { ReadLog(path, {}); });
  EXPECT_THAT(expected,
              AllOf(HasSubstr(fmt::format("log.txt:{}", bad_row + 2)),
                    HasSubstr("time goes back")));
  std::size_t handed_over = 0;
  double last_time_s = 0.0;
  const std::string streamed = MessageOf([&] {
    ReadLogRows(path, {}, [&](const Recording& piece) {
      handed_over += piece.size();
      last_time_s = piece.time_s.back();
    });
  });
  EXPECT_EQ(streamed, expected);
  EXPECT_EQ(handed_over, static_cast<std::size_t>(bad_row));
  EXPECT_DOUBLE_EQ(last_time_s, 1000.0 + (bad_row - 1) * 0.0025);
}

TEST(ReadLogRows, MalformedLineWithDataAfterItThrowsAsReadLog) {
  ScratchDir dir;
  const std::string path =
      dir.Write("log.txt", LongLog(40000, 0, 0) + "1100,0.1,0.2\n1100.5,0,0,9.8,0,0,0\n");
  const std::string expected = MessageOf([&] { ReadLog(path, {}); });
  EXPECT_THAT(expected, HasSubstr("log.txt:40002"));
  std::size_t handed_over = 0;
  EXPECT_EQ(MessageOf([&] {
              ReadLogRows(
                  path, {}, [&](const Recording& piece) { handed_over += piece.size(); });
            }),
            expected);
  EXPECT_EQ(handed_over, 40000u);
}

TEST(ReadLogRows, NoDataRowsThrowsAsReadLog) {
  ScratchDir dir;
  const std::string path = dir.Write("log.txt", "t,ax,ay,az\n");
  const std::string expected = MessageOf([&] { ReadLog(path, {}); });
  EXPECT_THAT(expected, HasSubstr("no data rows"));
  bool called = false;
  EXPECT_EQ(MessageOf([&] {
              ReadLogRows(path, {}, [&called](const Recording&) { called = true; });
            }),
            expected);
  EXPECT_FALSE(called);
}

TEST(ReadLogRows, WithoutAConsumerGivesTheSummary) {
  ScratchDir dir;
  const LogStreamSummary s =
      ReadLogRows(dir.Write("log.txt", LongLog(20000, 0, 0)), {}, nullptr);
  EXPECT_EQ(s.rows, 20000u);
  EXPECT_TRUE(s.has_gyro);
  EXPECT_DOUBLE_EQ(s.first_time_s, 1000.0);
  EXPECT_TRUE(s.warnings.empty());
}

}  // namespace
}  // namespace mpcal
