// The row sink's rules on their own: duplicates, time going back, the
// cut-off last line, gaps, streaming, progress.
#include "io/row_sink.h"

#include <algorithm>
#include <span>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mpcal/error.h"

namespace mpcal::logio {
namespace {

using ::testing::HasSubstr;

// A chunk of data lines "t,0,0,1" (one a line, no header), parsed.
ChunkRows Chunk(const std::string& bytes, const std::vector<double>& times) {
  ChunkRows c;
  c.bytes = bytes;
  c.time = times;
  c.accel.assign(times.size(), Eigen::Vector3d(0, 0, 1));
  c.lines = static_cast<std::size_t>(std::count(bytes.begin(), bytes.end(), '\n'));
  c.last_row_line = times.size();
  c.first_row_bytes = bytes.find('\n') + 1;
  c.has_content = !times.empty();
  return c;
}

std::string Lines(const std::vector<double>& times) {
  std::string out;
  for (double t : times) out += std::to_string(t) + ",0,0,1\n";
  return out;
}

TEST(RowSink, DuplicatesAreDroppedAndCountedAcrossChunks) {
  Recording rec;
  rec.source = "log";
  RowSink sink(&rec, 1.0, false, /*line_base=*/1, 0);
  const std::string a = Lines({1, 2, 2, 3});
  const std::string b = Lines({3, 4});
  sink.Append(Chunk(a, {1, 2, 2, 3}));
  sink.Append(Chunk(b, {3, 4}));
  sink.Finish(true);
  EXPECT_EQ(rec.time_s, (std::vector<double>{1, 2, 3, 4}));
  ASSERT_EQ(rec.accel.size(), 4u);
  ASSERT_EQ(rec.warnings.size(), 1u);
  // Line 1 is the header: the first duplicate is the third row, line 4.
  EXPECT_THAT(rec.warnings[0],
              HasSubstr("2 rows with a duplicated timestamp dropped "
                        "(first on line 4)"));
}

TEST(RowSink, TimeGoingBackIsRefusedWithBothLines) {
  Recording rec;
  rec.source = "log";
  RowSink sink(&rec, 1.0, false, 0, 0);
  sink.Append(Chunk(Lines({1, 2}), {1, 2}));
  try {
    sink.Append(Chunk(Lines({3, 1.5}), {3, 1.5}));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kTime);
    EXPECT_THAT(e.what(), HasSubstr("log:4: time goes back: 1.5 s after 3 s on line 3"));
  }
}

TEST(RowSink, WrappedCounterIsNamed) {
  Recording rec;
  rec.source = "log";
  RowSink sink(&rec, 1e-3, false, 0, 0);
  try {
    sink.Append(Chunk(Lines({65530, 3}), {65.530, 0.003}));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("16-bit counter that wrapped around at 65536"));
    EXPECT_THAT(e.what(), ::testing::Not(HasSubstr("--")));
  }
}

TEST(RowSink, MalformedLineIsFatalOnlyWhenDataFollows) {
  ChunkRows bad = Chunk(Lines({1, 2}) + "3,0,0\n", {1, 2});
  bad.failure_line = 3;
  bad.failure = "too few";
  {
    Recording rec;
    rec.source = "log";
    RowSink sink(&rec, 1.0, false, 0, 0);
    sink.Append(bad);
    sink.Append(Chunk("\n\n", {}));  // blank lines only: still the last line
    sink.Finish(false);
    EXPECT_EQ(rec.size(), 2u);
    ASSERT_EQ(rec.warnings.size(), 1u);
    EXPECT_THAT(rec.warnings[0], HasSubstr("log:3: last line is incomplete (too few)"));
  }
  {
    Recording rec;
    rec.source = "log";
    RowSink sink(&rec, 1.0, false, 0, 0);
    sink.Append(bad);
    EXPECT_THROW(sink.Append(Chunk(Lines({4}), {4})), Error);
  }
}

TEST(RowSink, StreamingHandsEachChunkOverAndWarnsAsHolding) {
  // A duplicate and a gap across the chunks' boundary.
  const std::vector<double> a_times = {1, 2, 3};
  const std::vector<double> b_times = {3, 9, 10, 11};
  const std::string a = Lines(a_times);
  const std::string b = Lines(b_times);
  Recording held;
  held.source = "log";
  RowSink holding(&held, 1.0, false, 0, 0);
  holding.Append(Chunk(a, a_times));
  holding.Append(Chunk(b, b_times));
  holding.Finish(false);

  Recording rec;
  rec.source = "log";
  RowSink streaming(&rec, 1.0, false, 0, 0);
  std::vector<std::vector<double>> pieces;
  streaming.StreamTo([&pieces](const Recording& r) { pieces.push_back(r.time_s); });
  streaming.Append(Chunk(a, a_times));
  EXPECT_TRUE(rec.time_s.empty() && rec.accel.empty());
  streaming.Append(Chunk(b, b_times));
  streaming.Finish(false);
  EXPECT_EQ(pieces, (std::vector<std::vector<double>>{{1, 2, 3}, {9, 10, 11}}));
  EXPECT_EQ(streaming.rows(), 6u);
  EXPECT_EQ(streaming.first_time_s(), 1.0);
  EXPECT_EQ(streaming.last_time_s(), 11.0);
  EXPECT_EQ(rec.warnings, held.warnings);
  ASSERT_EQ(rec.warnings.size(), 2u);
  EXPECT_THAT(rec.warnings[1],
              HasSubstr("1 gap in time longer than 5 sample periods (1 s); "
                        "the largest is 6 s after t = 3 s"));
}

TEST(RowSink, StreamingRefusesTimeGoingBackAcrossChunks) {
  Recording rec;
  rec.source = "log";
  RowSink sink(&rec, 1.0, false, 0, 0);
  std::size_t handed_over = 0;
  sink.StreamTo([&handed_over](const Recording& r) { handed_over += r.size(); });
  sink.Append(Chunk(Lines({1, 2}), {1, 2}));
  try {
    sink.Append(Chunk(Lines({3, 1.5}), {3, 1.5}));
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("log:4: time goes back: 1.5 s after 3 s on line 3"));
  }
  EXPECT_EQ(handed_over, 3u);  // the rows before the error
}

// 25,001 times 10 ms apart but for three gaps, one where the typical step
// becomes known (after 10,000 steps).
std::vector<double> TimesWithGaps() {
  std::vector<double> t;
  double now = 0.0;
  for (int i = 0; i <= 25000; ++i) {
    if (i == 5000) now += 0.2;
    if (i == 10000) now += 0.3;
    if (i == 20000) now += 0.25;
    t.push_back(now);
    now += 0.01;
  }
  return t;
}

// The reader's warning once every time was added.
std::string Warning(GapCounter& gaps) {
  gaps.Finish();
  return GapWarning(gaps, "log");
}

TEST(GapCounter, SameWarningWhateverThePieces) {
  const std::vector<double> t = TimesWithGaps();
  GapCounter whole = ReaderGapCounter();
  whole.Add(t);
  const std::string expected = Warning(whole);
  EXPECT_THAT(expected,
              HasSubstr("log: 3 gaps in time longer than 5 sample periods (0.01 s); "
                        "the largest is 0.31 s after t = 100.19 s"));
  for (const std::size_t piece : {1u, 7u, 9999u, 10000u, 10001u, 12345u}) {
    GapCounter counter = ReaderGapCounter();
    for (std::size_t i = 0; i < t.size(); i += piece) {
      counter.Add(std::span<const double>(t).subspan(i, std::min(piece, t.size() - i)));
    }
    EXPECT_EQ(Warning(counter), expected) << "pieces of " << piece;
  }
}

TEST(GapCounter, TypicalStepFromTheFirstStepsOnly) {
  // 10,000 steps of 10 ms, then 20,000 of 100 ms: the typical step is the
  // first steps' (a median over the whole would be 100 ms and see no gap).
  std::vector<double> t;
  for (int i = 0; i <= 10000; ++i) t.push_back(0.01 * i);
  for (int i = 1; i <= 20000; ++i) t.push_back(100.0 + 0.1 * i);
  GapCounter counter = ReaderGapCounter();
  counter.Add(t);
  EXPECT_THAT(Warning(counter),
              HasSubstr("20000 gaps in time longer than 5 sample "
                        "periods (0.01 s)"));
}

TEST(GapCounter, NothingToSayForFewTimesOrNoGap) {
  GapCounter two = ReaderGapCounter();
  two.Add(std::vector<double>{0.0, 5.0});
  EXPECT_EQ(Warning(two), "");
  GapCounter regular = ReaderGapCounter();
  regular.Add(std::vector<double>{0.0, 0.01, 0.02, 0.03, 0.04});
  EXPECT_EQ(Warning(regular), "");
}

TEST(ProgressReporter, AtMostAHundredReportsInOrderEndingAtOne) {
  std::vector<double> seen;
  ProgressReporter progress([&seen](double f) { seen.push_back(f); }, 100000);
  for (std::uint64_t done = 0; done <= 100000; done += 7) progress.Update(done);
  progress.Finish();
  ASSERT_FALSE(seen.empty());
  EXPECT_LE(seen.size(), 102u);
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end()));
  EXPECT_EQ(seen.back(), 1.0);
}

}  // namespace
}  // namespace mpcal::logio
