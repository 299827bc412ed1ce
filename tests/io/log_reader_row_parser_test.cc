// The one row parser: the values it reads, the fields it accepts, and why
// it refuses a row.
#include "io/row_parser.h"

#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "io/log_layout.h"

namespace mpcal::logio {
namespace {

using ::testing::HasSubstr;

struct Parsed {
  bool ok = false;
  LogLine line;
  std::string problem;
};

// Parses `row` with the layout found from `head` (a header and good rows).
Parsed ParseRow(const std::string& head, const std::string& row) {
  const auto d = DetectLayout(head, true, "log", {}, true);
  const RowParser parser(d.layout, d.roles, AccelUnits::kMps2);
  Parsed out;
  RowFailure why;
  out.ok = parser.Parse(row, &out.line, &why);
  if (!out.ok) out.problem = parser.Problem(row, why);
  return out;
}

TEST(RowParser, PlainQuotedSignedAndBlankPaddedFieldsGiveTheSameValues) {
  for (const std::string row : {"0.5,1.25,-2,9.75",
                                "\"0.5\",\"1.25\",\"-2\",\"9.75\"",
                                " 0.5 , +1.25,-2 ,9.75"}) {
    const Parsed p = ParseRow("t,ax,ay,az\n0,0,0,1\n", row);
    ASSERT_TRUE(p.ok) << row << ": " << p.problem;
    EXPECT_EQ(p.line.time_raw, 0.5) << row;
    EXPECT_EQ(p.line.accel, Eigen::Vector3d(1.25, -2, 9.75)) << row;
  }
}

TEST(RowParser, SpansLocateEachReading) {
  const std::string row = "0.5,1.25,\"-2\",9.75,0.1,0.2,0.3";
  const Parsed p = ParseRow("t,ax,ay,az,gx,gy,gz\n0,0,0,1,0,0,0\n", row);
  ASSERT_TRUE(p.ok) << p.problem;
  const auto [b, e] = p.line.accel_span[1];
  EXPECT_EQ(row.substr(b, e - b), "-2");
  const auto [gb, ge] = p.line.gyro_span[2];
  EXPECT_EQ(row.substr(gb, ge - gb), "0.3");
  EXPECT_EQ(p.line.gyro.z(), 0.3);
}

// ReadLog's fast path (ParseInChunk, which finds the line's end as it
// parses) must accept a line only when Parse does, with the same values,
// and say where the next line starts; what it declines goes to Parse.
void ExpectFastPathAgrees(const std::string& head,
                          const std::string& line,
                          const std::string& eol,
                          bool fast_expected) {
  const auto d = DetectLayout(head, true, "log", {}, true);
  const RowParser parser(d.layout, d.roles, AccelUnits::kMps2);
  // The line, then another (none after a last line without its end).
  const std::string chunk = eol.empty() ? line : line + eol + "0,0,0,1,0,0,0\n";
  double by_role[kGz + 1] = {};
  const char* next =
      parser.ParseInChunk(chunk.data(), chunk.data() + chunk.size(), by_role);
  LogLine reference;
  RowFailure why;
  const bool ok = parser.Parse(line, &reference, &why);
  EXPECT_EQ(next != nullptr, fast_expected) << "'" << line << "'";
  if (next == nullptr) return;
  ASSERT_TRUE(ok) << "fast path accepted what Parse refuses: '" << line << "'";
  EXPECT_EQ(next, chunk.data() + line.size() + eol.size()) << "'" << line << "'";
  EXPECT_EQ(by_role[kTime], reference.time_raw) << line;
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(by_role[kAx + i], reference.accel[i]) << line;
    if (d.layout.has_gyro()) {
      EXPECT_EQ(by_role[kGx + i], reference.gyro[i]) << line;
    }
  }
}

TEST(RowParser, FastPathAgreesWithParse) {
  const std::string csv = "t,ax,ay,az,gx,gy,gz\n0,0,0,1,0,0,0\n";
  for (const std::string eol : {"\n", "\r\n"}) {
    ExpectFastPathAgrees(csv, "0.5,1.25,-2,9.75,0.1,0.2,0.3", eol, true);
    ExpectFastPathAgrees(csv, "\"0.5\",\"1.25\",-2,9.75,0.1,0.2,+0.3", eol, true);
    ExpectFastPathAgrees(csv, " 0.5 , 1.25,-2 ,9.75,0.1,0.2,0.3  ", eol, true);
    ExpectFastPathAgrees(csv, "0.5,1.25,-2,9.75,0.1,0.2,0.3,extra,7", eol, true);
    // Declined: Parse gives the verdict (and the message).
    ExpectFastPathAgrees(csv, "0.5,1.25,-2,9.75,0.1,0.2", eol, false);
    ExpectFastPathAgrees(csv, "0.5,1.25\r,-2,9.75,0.1,0.2,0.3", eol, false);
    ExpectFastPathAgrees(csv, "0.5,1.25,-2,9.75,0.1,0.2,x", eol, false);
    ExpectFastPathAgrees(csv, "0.5,1.25,-2,1e300,0.1,0.2,0.3", eol, false);
    ExpectFastPathAgrees(csv, "# 0.5,1.25,-2,9.75,0.1,0.2,0.3", eol, false);
    ExpectFastPathAgrees(csv, "", eol, false);
  }
  // A stray '\r' before the line's "\r\n" is not part of its end.
  ExpectFastPathAgrees(csv, "0.5,1.25,-2,9.75,0.1,0.2,0.3\r", "\r\n", false);
  const std::string blanks = "t ax ay az\n0 0 0 1\n";
  ExpectFastPathAgrees(blanks, "  0.5   1 2\t3", "\n", true);
  ExpectFastPathAgrees(blanks, "0.5 1 2 3  ", "\r\n", true);
  ExpectFastPathAgrees(blanks, "0.5 1 2 3 4 5", "\n", true);
  ExpectFastPathAgrees(blanks, "0.5 1 2", "\n", false);
  // The last line of the input, without its end.
  ExpectFastPathAgrees(csv, "0.5,1.25,-2,9.75,0.1,0.2,0.3", "", true);
}

TEST(RowParser, BlankSeparatedRows) {
  const Parsed p = ParseRow("t ax ay az\n0 0 0 1\n", "  0.5   1 2\t3  ");
  ASSERT_TRUE(p.ok) << p.problem;
  EXPECT_EQ(p.line.accel, Eigen::Vector3d(1, 2, 3));
}

TEST(RowParser, RefusesWithTheReason) {
  const std::string kHead = "t,ax,ay,az\n0,0,0,1\n";
  EXPECT_THAT(ParseRow(kHead, "0.5,1,2").problem,
              HasSubstr("expected at least 4 columns separated by commas"));
  EXPECT_THAT(ParseRow(kHead, "0.5,1,abc,3").problem,
              HasSubstr("expected a number in column 'ay' (index 2), found 'abc'"));
  EXPECT_THAT(ParseRow(kHead, "0.5,1,,3").problem,
              HasSubstr("column 'ay' (index 2) is empty"));
  EXPECT_THAT(ParseRow(kHead, "0.5,1,nan,3").problem,
              HasSubstr("non-finite value 'nan' in column 'ay'"));
  EXPECT_THAT(ParseRow(kHead, "0.5,1,1e300,3").problem,
              HasSubstr("beyond any accelerometer's range"));
  EXPECT_THAT(ParseRow(kHead, "0.5,1,+-2,3").problem, HasSubstr("found '+-2'"));
  EXPECT_THAT(ParseRow(kHead, "0.5,1,2 x,3").problem, HasSubstr("found '2 x'"));
}

TEST(RowParser, ColumnsNoRoleNeedsAreNotRead) {
  // The text column is skipped, not converted: the row is good.
  const Parsed p = ParseRow("t,note,ax,ay,az\n0,x,0,0,1\n", "0.5,hello,1,2,3");
  ASSERT_TRUE(p.ok) << p.problem;
  EXPECT_EQ(p.line.accel, Eigen::Vector3d(1, 2, 3));
}

}  // namespace
}  // namespace mpcal::logio
