// The steps of ApplyCalibration on their own (src/apply/apply_steps.h).
#include "apply/apply_steps.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mpcal/units.h"

namespace mpcal::internal {
namespace {

using ::testing::HasSubstr;

TEST(CheckRestMagnitude, WithinToleranceIsNoFinding) {
  EXPECT_FALSE(CheckRestMagnitude({9.81, 9.81}, 9.81, 0.05, AccelUnits::kMps2, "a.csv"));
  EXPECT_FALSE(CheckRestMagnitude({10.2, 10.2}, 9.81, 0.05, AccelUnits::kMps2, "a.csv"));
}

TEST(CheckRestMagnitude, AFactorOfGravityIsAUnitsMixUp) {
  // A log in g read as m/s²: the raw readings are about 1 at rest.
  const auto in_g =
      CheckRestMagnitude({1.0, 1.0}, 9.81, 0.05, AccelUnits::kMps2, "a.csv");
  ASSERT_TRUE(in_g);
  EXPECT_EQ(in_g->kind, RestMismatchKind::kLooksLikeG);
  EXPECT_THAT(in_g->what, HasSubstr("a.csv: the corrected magnitude at rest is 1 m/s²"));
  EXPECT_THAT(in_g->what, HasSubstr("-89.8% from the calibration's gravity 9.81 m/s²"));
  ASSERT_EQ(in_g->advice.settings.size(), 1u);
  EXPECT_EQ(in_g->advice.settings[0].value, "g");
  // A log in m/s² read as g: about 9.8 × 9.8.
  const double read_as_g = 9.81 * kStandardGravityMps2;
  const auto in_mps2 =
      CheckRestMagnitude({read_as_g, read_as_g}, 9.81, 0.05, AccelUnits::kG, "a.csv");
  ASSERT_TRUE(in_mps2);
  EXPECT_EQ(in_mps2->kind, RestMismatchKind::kLooksLikeMps2);
  EXPECT_EQ(in_mps2->advice.settings[0].value, "mps2");
}

TEST(CheckRestMagnitude, AFewPercentIsAnotherSensorOrTheUnits) {
  const auto off = CheckRestMagnitude({10.5, 10.5}, 9.81, 0.05, AccelUnits::kMps2, "a");
  ASSERT_TRUE(off);
  EXPECT_EQ(off->kind, RestMismatchKind::kSensorOrUnits);
  ASSERT_EQ(off->advice.settings.size(), 1u);
  EXPECT_EQ(off->advice.settings[0].option, Option::kLogUnits);
  EXPECT_TRUE(off->advice.settings[0].value.empty());
  // In counts the raw readings have no fixed scale to tell a mix-up by.
  const auto counts =
      CheckRestMagnitude({1.0, 1.0}, 9.81, 0.05, AccelUnits::kCounts, "a");
  ASSERT_TRUE(counts);
  EXPECT_EQ(counts->kind, RestMismatchKind::kSensorOrUnits);
}

TEST(RestSummary, TheQuietestBlocksGiveTheMagnitude) {
  RestSummary summary(1.0);
  EXPECT_FALSE(RestSummary(1.0).Finish());
  // 32 rows at rest at 9.8, then 96 rows shaking about a mean of 12.
  for (int i = 0; i < 32; ++i) summary.Add({0, 0, 9.8}, {0, 0, 9.8});
  for (int i = 0; i < 96; ++i) {
    const double shake = i % 2 == 0 ? 3.0 : -3.0;
    summary.Add({shake, 0, 12.0}, {shake, 0, 12.0});
  }
  const std::optional<Rest> rest = summary.Finish();
  ASSERT_TRUE(rest);
  EXPECT_NEAR(rest->magnitude_mps2, 9.8, 1e-12);
  EXPECT_NEAR(rest->raw_magnitude_mps2, 9.8, 1e-12);
}

TEST(AppendCorrectedRow, ReplacesTheNumbersInTheOrderTheyAppear) {
  LogLine line;
  line.text = "0.5;az=3,0;ay=2,0;ax=1,0";
  line.eol = "\r\n";
  // x, y, z spans as they lie on the line: z first.
  line.accel_span = {{{21, 24}, {14, 17}, {7, 10}}};
  Eigen::Matrix<double, 6, 1> values;
  values << 1.25, 2.5, -3.0, 0, 0, 0;
  std::string out;
  AppendCorrectedRow(line, values, 3, ',', out);
  EXPECT_EQ(out, "0.5;az=-3;ay=2,5;ax=1,25\r\n");
}

TEST(RelabelHeader, AccelerometerUnitsFollowTheOutput) {
  LogLayout layout;
  layout.delimiter = ',';
  layout.accel_columns = {1, 2, 3};
  EXPECT_EQ(RelabelHeader("t (s),ax (m/s^2),ay (m/s^2),az [m/s2],T (m/s^2)",
                          layout,
                          AccelUnits::kMps2,
                          AccelUnits::kG),
            "t (s),ax (g),ay (g),az [g],T (m/s^2)");
  EXPECT_EQ(RelabelHeader("t,ax (g)", layout, AccelUnits::kG, AccelUnits::kG),
            "t,ax (g)");
}

}  // namespace
}  // namespace mpcal::internal
