// The shared text helpers (src/text/text.h) the readers rely on.
#include "text/text.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace mpcal::text {
namespace {

using ::testing::ElementsAre;

TEST(Text, LowerFoldsAsciiOnly) {
  EXPECT_EQ(Lower("Acc_X [M/S2]"), "acc_x [m/s2]");
  EXPECT_EQ(Lower("\xC3\x84x"), "\xC3\x84x");  // UTF-8 bytes left alone
}

TEST(Text, TrimDropsSpacesTabsAndLineEnds) {
  EXPECT_EQ(Trim(" \t a b \r\n"), "a b");
  EXPECT_EQ(Trim(" \t\r\n"), "");
  EXPECT_EQ(Trim(""), "");
}

TEST(Text, SplitOnKeepsEmptyFieldsAndTrimsEach) {
  EXPECT_THAT(SplitOn(" a , b ,", ','), ElementsAre("a", "b", ""));
  EXPECT_THAT(SplitOn("", ','), ElementsAre(""));
  EXPECT_THAT(SplitOn("1;2", ';'), ElementsAre("1", "2"));
}

TEST(Text, SplitWhitespaceGivesTheRuns) {
  EXPECT_THAT(SplitWhitespace("  1 \t 2  3 "), ElementsAre("1", "2", "3"));
  EXPECT_TRUE(SplitWhitespace(" \t ").empty());
}

TEST(Text, LinesCutAtLfAndDropCr) {
  EXPECT_THAT(Lines("a\r\nb\n\nc"), ElementsAre("a", "b", "", "c"));
  EXPECT_THAT(Lines("a\n"), ElementsAre("a"));
  EXPECT_TRUE(Lines("").empty());
}

}  // namespace
}  // namespace mpcal::text
