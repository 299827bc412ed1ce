// The row sink's rules on their own: duplicates, time going back, the
// cut-off last line, progress.
#include "io/row_sink.h"

#include <algorithm>
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
