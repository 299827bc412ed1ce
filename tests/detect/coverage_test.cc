#include "mpcal/coverage.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <Eigen/Geometry>

#include "findings.h"
#include "mpcal/error.h"
#include "mpcal/log_reader.h"
#include "mpcal/units.h"
#include "test_util.h"

namespace mpcal {
namespace {

using test::Names;
using test::Words;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::Not;

constexpr double kDeg = std::numbers::pi / 180.0;

std::vector<Eigen::Vector3d> Cube26() {
  std::vector<Eigen::Vector3d> out;
  for (const auto& c : CanonicalDirections()) out.push_back(c.direction);
  return out;
}

// Mean readings of a sensor with an offset and a common scale at `dirs`,
// each tilted by `tilt_deg` about a fixed skew axis.
std::vector<Eigen::Vector3d> Readings(const std::vector<Eigen::Vector3d>& dirs,
                                      double scale,
                                      const Eigen::Vector3d& offset,
                                      double tilt_deg = 0.0) {
  const Eigen::AngleAxisd tilt(tilt_deg * kDeg, Eigen::Vector3d(1, 2, 3).normalized());
  std::vector<Eigen::Vector3d> out;
  for (const auto& d : dirs) out.push_back(offset + scale * (tilt * d));
  return out;
}

TEST(CanonicalDirections, AreTheFacesEdgesAndCornersOfACube) {
  const auto& c = CanonicalDirections();
  ASSERT_EQ(c.size(), 26u);
  int kinds[3] = {0, 0, 0};
  for (std::size_t i = 0; i < c.size(); ++i) {
    EXPECT_NEAR(c[i].direction.norm(), 1.0, 1e-15);
    ++kinds[static_cast<int>(c[i].kind)];
    for (std::size_t j = i + 1; j < c.size(); ++j) {
      // Neighbours on the cube are 35.3° (edge-corner) or more apart.
      EXPECT_LT(c[i].direction.dot(c[j].direction), std::cos(35.0 * kDeg));
    }
  }
  EXPECT_EQ(kinds[0], 6);
  EXPECT_EQ(kinds[1], 12);
  EXPECT_EQ(kinds[2], 8);
  // The label names what points down: +z up is the -z face down.
  EXPECT_EQ(c[4].direction, Eigen::Vector3d::UnitZ());
  EXPECT_EQ(c[4].down, "-z face");
  EXPECT_EQ(c.back().down, "+x+y+z corner");
}

TEST(FitSphere, RecoversTheOffsetOfRawCounts) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> noise(0.0, 0.5);
  const Eigen::Vector3d offset(32768 + 340, 32768 - 120, 32768 + 60);
  auto means = Readings(Cube26(), 4000.0, offset, 4.0);
  for (auto& m : means) m += Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
  const SphereFit fit = FitSphere(means, AccelUnits::kCounts);
  EXPECT_TRUE(fit.fitted);
  // 26 means with 0.5-count noise: the centre to well within 1 count.
  EXPECT_LT((fit.centre - offset).norm(), 1.0);
  EXPECT_NEAR(fit.radius, 4000.0, 1.0);
  EXPECT_LT(fit.residual_rms, 1.0);
}

TEST(FitSphere, FallsBackWhenThePositionsDoNotSpanTheSphere) {
  // Three positions: too few for a fit.
  const std::vector<Eigen::Vector3d> dirs = {
      Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX(), -Eigen::Vector3d::UnitY()};
  const SphereFit counts = FitSphere(
      Readings(dirs, 4000.0, Eigen::Vector3d::Constant(32768)), AccelUnits::kCounts);
  EXPECT_FALSE(counts.fitted);
  EXPECT_EQ(counts.centre, Eigen::Vector3d::Constant(32768));
  EXPECT_NEAR(counts.radius, 4000.0, 1e-9);
  const SphereFit mps2 = FitSphere(
      Readings(dirs, kStandardGravityMps2, Eigen::Vector3d::Zero()), AccelUnits::kMps2);
  EXPECT_FALSE(mps2.fitted);
  EXPECT_EQ(mps2.centre, Eigen::Vector3d::Zero());
  // Signed counts (a negative reading): no unsigned offset.
  const SphereFit signed_counts =
      FitSphere(Readings(dirs, 1000.0, Eigen::Vector3d::Zero()), AccelUnits::kCounts);
  EXPECT_EQ(signed_counts.centre, Eigen::Vector3d::Zero());
  // Nothing at all.
  EXPECT_EQ(FitSphere({}, AccelUnits::kG).radius, 0.0);
}

TEST(FitSphere, IgnoresAFitThroughPositionsOnOneSmallCap) {
  // Five positions within 20° of +z: any centre on the z axis fits them.
  std::vector<Eigen::Vector3d> dirs;
  for (int k = 0; k < 5; ++k) {
    dirs.push_back(
        Eigen::Vector3d(0.3 * std::cos(k), 0.3 * std::sin(k), 1.0).normalized());
  }
  std::vector<Eigen::Vector3d> means =
      Readings(dirs, kStandardGravityMps2, Eigen::Vector3d::Zero());
  means[2].z() += 0.05;  // noise the cap cannot resolve
  const SphereFit fit = FitSphere(means, AccelUnits::kMps2);
  EXPECT_FALSE(fit.fitted);
  EXPECT_EQ(fit.centre, Eigen::Vector3d::Zero());
}

TEST(AssessCoverage, TheTwentySixCubePositionsAreGood) {
  CoverageOptions o;
  o.units = AccelUnits::kCounts;
  const CoverageResult r = AssessCoverage(
      Readings(Cube26(), 4000.0, Eigen::Vector3d::Constant(32900), 5.0), o);
  EXPECT_EQ(r.verdict, CoverageVerdict::kGood) << Summary(r);
  EXPECT_TRUE(r.good_enough());
  EXPECT_EQ(r.covered.size(), 26u);
  EXPECT_TRUE(r.missing.empty());
  EXPECT_EQ(r.positions, 26);
  EXPECT_EQ(r.distinct_positions, 26);
  for (const AxisCoverage& ax : r.axes) {
    EXPECT_TRUE(ax.near_up && ax.near_down);
    EXPECT_NEAR(ax.closest_up_deg, 5.0, 5.0);
    EXPECT_NEAR(ax.largest_gap_deg, 45.0, 10.0);
  }
  // The middle of a face-edge-corner triangle is about 20-25° from all three.
  EXPECT_LT(r.largest_empty_cap_deg, 30.0);
  EXPECT_GT(r.observability, 0.1);
  EXPECT_TRUE(r.problems.empty());
  EXPECT_TRUE(r.advice.empty());
  EXPECT_THAT(Summary(r), HasSubstr("good: 26 static positions"));
  EXPECT_EQ(r.required_positions, 10);
}

TEST(AssessCoverage, SixFacesAreNotEnoughForNineParameters) {
  const auto& c = CanonicalDirections();
  std::vector<Eigen::Vector3d> dirs;
  for (int i = 0; i < 6; ++i) dirs.push_back(c[static_cast<std::size_t>(i)].direction);
  dirs.push_back(c[4].direction);  // the rest at the start, +z up again
  const auto means =
      Readings(dirs, kStandardGravityMps2, Eigen::Vector3d(0.2, -0.1, 0.3));
  const CoverageResult r = AssessCoverage(means, {});
  EXPECT_EQ(r.verdict, CoverageVerdict::kNotEnough);
  EXPECT_FALSE(r.good_enough());
  EXPECT_EQ(r.distinct_positions, 6);
  EXPECT_THAT(
      Summary(r),
      AllOf(HasSubstr("session has 7 static positions, the 9-parameter model needs at "
                      "least 10: record 3 more positions"),
            HasSubstr("corner"),
            HasSubstr("6-parameter model")));
  // The same positions are what the six-position protocol needs.
  CoverageOptions six;
  six.model = ModelKind::kBiasScale6;
  const CoverageResult r6 = AssessCoverage(means, six);
  EXPECT_EQ(r6.verdict, CoverageVerdict::kGood) << Summary(r6);
  EXPECT_EQ(r6.required_positions, 6);
  // The six poses alone fit exactly: usable, with the warning that nothing
  // checks them.
  const std::vector<Eigen::Vector3d> six_poses(means.begin(), means.begin() + 6);
  const CoverageResult exact = AssessCoverage(six_poses, six);
  EXPECT_EQ(exact.verdict, CoverageVerdict::kUsableWithWarnings) << Summary(exact);
  EXPECT_THAT(Words(exact.problems),
              ::testing::Contains(HasSubstr("nothing checks the fit")));
  // Under the 9-parameter model the advice offers the six-position protocol
  // once.
  const CoverageResult nine = AssessCoverage(six_poses, {});
  ASSERT_EQ(nine.advice.size(), 2u);
  EXPECT_EQ(nine.advice[1].kind, CoverageStepKind::kSixParameterModel);
  ASSERT_TRUE(Names(nine.advice[1].advice, Option::kModel));
  EXPECT_EQ(nine.advice[1].advice.settings.front().value, "bias-scale-6");
  EXPECT_THAT(Summary(nine), HasSubstr("6-parameter model"));
  EXPECT_EQ(Summary(nine).find("6-parameter"), Summary(nine).rfind("6-parameter"));
}

TEST(AssessCoverage, SaysToHoldLongerWhenPositionsWereDroppedAsTooShort) {
  // Four positions kept, twenty held too briefly: recording more the same
  // way would not help.
  DetectResult det;
  for (const auto& m :
       Readings(Cube26(), kStandardGravityMps2, Eigen::Vector3d::Zero())) {
    if (det.intervals.size() == 4) break;
    StaticInterval iv;
    iv.mean = m;
    det.intervals.push_back(iv);
  }
  det.dropped_short = 20;
  const CoverageResult r = AssessCoverage(det, {});
  EXPECT_EQ(r.verdict, CoverageVerdict::kNotEnough);
  EXPECT_THAT(
      Summary(r),
      HasSubstr("session has 4 static positions, the 9-parameter model needs at "
                "least 10: 20 still stretches shorter than the minimum static time "
                "were dropped: hold each position longer; record"));
  ASSERT_FALSE(r.advice.empty());
  EXPECT_EQ(r.advice.front().kind, CoverageStepKind::kHoldLonger);
  EXPECT_TRUE(Names(r.advice.front().advice, Option::kDetectMinStatic));
  // Fewer dropped than kept: stray pauses, not the way the session was held.
  det.dropped_short = 3;
  EXPECT_THAT(Summary(AssessCoverage(det, {})),
              Not(HasSubstr("hold each position longer")));
}

TEST(AssessCoverage, NamesTheFacesNeverDown) {
  // Eleven positions, none with +y or -z down (no reading near -y or +z).
  std::vector<Eigen::Vector3d> dirs;
  for (const auto& c : CanonicalDirections()) {
    if (c.direction.y() < -0.1 || c.direction.z() > 0.1) continue;
    dirs.push_back(c.direction);
  }
  ASSERT_EQ(dirs.size(), 11u);
  const CoverageResult r =
      AssessCoverage(Readings(dirs, kStandardGravityMps2, Eigen::Vector3d::Zero()), {});
  EXPECT_EQ(r.verdict, CoverageVerdict::kUsableWithWarnings) << Summary(r);
  EXPECT_FALSE(r.axes[1].near_down);
  EXPECT_FALSE(r.axes[2].near_up);
  EXPECT_TRUE(r.axes[0].near_up && r.axes[0].near_down);
  EXPECT_THAT(Words(r.problems), ::testing::Contains(HasSubstr("+y never pointed down")));
  EXPECT_THAT(Words(r.problems), ::testing::Contains(HasSubstr("+z never pointed up")));
  ASSERT_FALSE(r.advice.empty());
  // Faces first: +y down and -z down.
  EXPECT_THAT(Describe(r.advice.front()),
              HasSubstr("record 8 more positions, e.g. with the +y face, -z face, "));
}

TEST(AssessCoverage, PositionsInOnePlaneDoNotDetermineTheModel) {
  // Twelve positions turning about z only: every direction has z = 0.
  std::vector<Eigen::Vector3d> dirs;
  for (int k = 0; k < 12; ++k) {
    dirs.emplace_back(
        std::cos(k * std::numbers::pi / 6), std::sin(k * std::numbers::pi / 6), 0);
  }
  const CoverageResult r =
      AssessCoverage(Readings(dirs, kStandardGravityMps2, Eigen::Vector3d::Zero()), {});
  EXPECT_EQ(r.verdict, CoverageVerdict::kNotEnough);
  EXPECT_LT(r.observability, 1e-6);
  EXPECT_THAT(Summary(r), HasSubstr("do not determine all 9 parameters"));
  EXPECT_THAT(Summary(r), HasSubstr("face"));
}

TEST(AssessCoverage, TwelveSpreadPositionsAreUsableWithAWarning) {
  std::vector<Eigen::Vector3d> dirs;
  const auto& c = CanonicalDirections();
  for (int i : {0, 1, 2, 3, 4, 5, 18, 19, 20, 21, 22, 25}) {
    dirs.push_back(c[static_cast<std::size_t>(i)].direction);
  }
  const CoverageResult r = AssessCoverage(
      Readings(dirs, kStandardGravityMps2, Eigen::Vector3d::Zero(), 3.0), {});
  EXPECT_EQ(r.verdict, CoverageVerdict::kUsableWithWarnings) << Summary(r);
  EXPECT_THAT(Summary(r),
              HasSubstr("12 distinct orientations; the paper recommends more than 18"));
  EXPECT_THAT(Summary(r), HasSubstr("record 7 more positions"));
}

TEST(AssessCoverage, CountsRepeatedOrientationsOnce) {
  std::vector<Eigen::Vector3d> dirs = Cube26();
  for (int k = 0; k < 5; ++k) dirs.push_back(dirs[static_cast<std::size_t>(k)]);
  const CoverageResult r = AssessCoverage(
      Readings(dirs, kStandardGravityMps2, Eigen::Vector3d::Zero(), 2.0), {});
  EXPECT_EQ(r.positions, 31);
  EXPECT_EQ(r.distinct_positions, 26);
}

TEST(AssessCoverage, NoPositionAtAllIsNotEnoughAndDoesNotCrash) {
  const CoverageResult r = AssessCoverage(std::vector<Eigen::Vector3d>{}, {});
  EXPECT_EQ(r.verdict, CoverageVerdict::kNotEnough);
  EXPECT_EQ(r.missing.size(), 26u);
  EXPECT_THAT(Summary(r), HasSubstr("session has 0 static positions"));
}

TEST(AssessCoverage, RejectsBadInput) {
  std::vector<Eigen::Vector3d> means = Cube26();
  means[3].x() = std::numeric_limits<double>::infinity();
  EXPECT_THROW(AssessCoverage(means, {}), Error);
  CoverageOptions o;
  o.near_deg = 0.0;
  EXPECT_THAT(o.Validate(), HasSubstr("near_deg"));
  EXPECT_THROW(AssessCoverage(Cube26(), o), Error);
}

TEST(AssessCoverage, XsensSessionIsUsableForNineParameters) {
  LogOptions lo;
  lo.units = AccelUnits::kCounts;
  const Recording rec =
      ReadLog(testing::RealDataPath("xsens-multiposition/xsens_acc.mat"), lo);
  const DetectResult det = DetectStatic(rec, {});
  CoverageOptions o;
  o.units = AccelUnits::kCounts;
  const CoverageResult r = AssessCoverage(det, o);
  EXPECT_TRUE(r.normalisation.fitted);
  // An unsigned 16-bit ADC: zero near 32768, about 4000 counts per g (the
  // nominal scale of the Xsens part), within the bias of the device.
  EXPECT_LT(
      (r.normalisation.centre - Eigen::Vector3d::Constant(32768)).cwiseAbs().maxCoeff(),
      800.0);
  EXPECT_NEAR(r.normalisation.radius, 4000.0, 200.0);
  EXPECT_TRUE(r.good_enough()) << Summary(r);
  for (const AxisCoverage& ax : r.axes) EXPECT_TRUE(ax.near_up && ax.near_down);
  EXPECT_THAT(Summary(r), Not(HasSubstr("needs at least")));
}

}  // namespace
}  // namespace mpcal
