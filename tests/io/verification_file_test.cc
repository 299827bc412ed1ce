// The verification's files round trip through their writer and reader, both
// in io: the result JSON and the trajectory CSVs.
#include "mpcal/verification_file.h"

#include <limits>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mpcal/error.h"
#include "test_util.h"

namespace mpcal {
namespace {

using ::testing::Contains;
using ::testing::HasSubstr;
using ::testing::Pair;

VerifyResult Result() {
  VerifyResult r;
  r.time.method = TimeAlignMode::kMotionStart;
  r.time.offset_s = 18.25;
  r.reference.path_length_m = 129.5;
  r.reference.start_end_distance_m = 0.25;
  r.raw = PathMetrics{15.5, 6.125, 15.5, 133.0};
  r.corrected = PathMetrics{1.5, 0.75, 1.75, 130.5};
  r.mount = MountMode::kZUp;
  r.stops = 4;
  r.warnings = {"the log has gyroscope columns, but they were not used"};
  return r;
}

TEST(VerificationFile, ResultRoundTripsThroughItsReader) {
  const VerificationSummary v = ParseVerificationJson(
      VerificationToJson(Result(), {{"raw", "w-raw.csv"}}), "/run/result.json");
  EXPECT_EQ(v.reference.start_end_distance_m, 0.25);
  EXPECT_EQ(v.reference.path_length_m, 129.5);
  EXPECT_EQ(v.raw.start_end_distance_m, 15.5);
  EXPECT_EQ(v.raw.horizontal_rms_m, 6.125);
  ASSERT_TRUE(v.corrected);
  EXPECT_EQ(v.corrected->horizontal_max_m, 1.75);
  EXPECT_EQ(v.corrected->path_length_m, 130.5);
  // The file's words for the enums, and the figures as the JSON holds them.
  EXPECT_THAT(v.details, Contains(Pair("time_alignment.method", "motion")));
  EXPECT_THAT(v.details, Contains(Pair("time_alignment.offset_s", "18.25")));
  EXPECT_THAT(v.details, Contains(Pair("integration.mount", "z-up")));
  EXPECT_THAT(v.details, Contains(Pair("integration.stops", "4")));
  EXPECT_EQ(v.warnings, Result().warnings);
  ASSERT_EQ(v.trajectory_files.size(), 1u);
  EXPECT_EQ(v.trajectory_files[0].second, "/run/w-raw.csv");
}

TEST(VerificationFile, ReaderRefusesANegativeDistance) {
  VerifyResult r = Result();
  r.raw.start_end_distance_m = -15.5;
  EXPECT_THAT([&] { ParseVerificationJson(VerificationToJson(r, {}), "result.json"); },
              ::testing::ThrowsMessage<Error>(
                  HasSubstr("result.json: 'raw.start_end_distance_m' = -15.5 m is "
                            "negative: not a distance")));
  r = Result();
  r.reference.path_length_m = -1.0;
  EXPECT_THAT([&] { ParseVerificationJson(VerificationToJson(r, {}), "result.json"); },
              ::testing::ThrowsMessage<Error>(
                  HasSubstr("'reference.path_length_m' = -1 m is negative")));
}

// nlohmann would write a NaN as null, which reads as "absent": refused.
TEST(VerificationFile, WriterRefusesANonFiniteNumberNamingItsPath) {
  VerifyResult r = Result();
  r.corrected->horizontal_rms_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THAT([&] { VerificationToJson(r, {}); },
              ::testing::ThrowsMessage<Error>(
                  HasSubstr("cannot write the verification result: "
                            "'corrected.horizontal_rms_m' is not a finite number")));
}

TEST(VerificationFile, TrajectoryCsvRoundTripsToTheMillimetre) {
  TimedPath path;
  path.time_s = {0.0, 0.01, 0.02};
  path.position_m = {{0.0, 0.0, 0.0}, {1.23456, -2.5, 0.1}, {2.0, -5.00004, 0.2}};
  const mpcal::testing::ScratchDir dir;
  const EastNorthPath back =
      ReadEastNorthCsv(dir.Write("p.csv", PathToCsv(path, {1, 1, 2})));
  ASSERT_EQ(back.time_s.size(), 3u);
  for (std::size_t i = 0; i < 3; ++i) {
    EXPECT_NEAR(back.time_s[i], path.time_s[i], 5e-5);
    EXPECT_NEAR(back.east_m[i], path.position_m[i].x(), 5e-5);
    EXPECT_NEAR(back.north_m[i], path.position_m[i].y(), 5e-5);
  }
}

TEST(VerificationFile, MissingFilesAreIoErrorsNamingThePath) {
  const mpcal::testing::ScratchDir dir;
  try {
    ReadVerificationFile(dir.Path("none.json"));
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kIo);
    EXPECT_THAT(e.what(), HasSubstr("none.json: cannot open a verification result"));
  }
  try {
    ReadEastNorthCsv(dir.path().string());
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("is a directory, expected a trajectory CSV"));
  }
}

}  // namespace
}  // namespace mpcal
