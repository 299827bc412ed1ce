// Repeatability statistics on calibrations built by hand: the deviations, the
// chi-square verdict, and the refusal of trials that do not compare.
#include <cmath>
#include <optional>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mpcal/error.h"
#include "mpcal/repeat.h"
#include "test_util.h"

namespace mpcal {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

using testing::kArithmetic;

// The tail probabilities below are quoted from chi-square tables to 1e-12.
constexpr double kTableTolerance = 1e-9;

// The same device in three sessions: the bias of the second moved by 30σ at
// power-up, everything else within its 1σ. σ of a good calibration (MTi-G).
constexpr double kBiasStd = 2e-4;   // m/s²
constexpr double kScaleStd = 2e-5;  // dimensionless
constexpr double kAngleStd = 2e-5;  // rad

Calibration Trial(const Eigen::Vector3d& bias_offset_in_std,
                  const Eigen::Vector3d& scale_offset_in_std,
                  double angle_offset_in_std) {
  Calibration c;
  c.model.bias_mps2 = Eigen::Vector3d(0.12, 0.11, -0.14) + bias_offset_in_std * kBiasStd;
  c.model.scale_factor_error =
      Eigen::Vector3d(-2e-3, -1e-3, -1e-3) + scale_offset_in_std * kScaleStd;
  c.model.theta_yz_rad = 1e-5 + angle_offset_in_std * kAngleStd;
  c.model.theta_zx_rad = 1.8e-4 - angle_offset_in_std * kAngleStd;
  c.model.theta_zy_rad = 1.7e-4;
  ErrorModel std;
  std.bias_mps2.setConstant(kBiasStd);
  std.scale_factor_error.setConstant(kScaleStd);
  std.theta_yz_rad = std.theta_zx_rad = std.theta_zy_rad = kAngleStd;
  c.std = std;
  return c;
}

// A trial with every parameter at the device's value.
Calibration Still() {
  return Trial(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), 0.0);
}

std::vector<Calibration> BiasMovedInTrial2() {
  return {Trial({0.5, -0.3, 0.2}, {0.4, -0.6, 0.1}, 0.3),
          Trial({30.0, -0.5, 0.7}, {-0.2, 0.5, -0.8}, -0.4),
          Trial({-0.2, 0.9, -0.6}, {0.7, 0.2, 0.5}, 0.6)};
}

TEST(RepeatabilityOptions, DefaultsAreValid) {
  EXPECT_EQ(RepeatabilityOptions{}.Validate(), "");
  RepeatabilityOptions bad;
  bad.significance = 1.0;
  EXPECT_THAT(bad.Validate(), HasSubstr("significance"));
  bad = {};
  bad.gravity_tolerance_mps2 = -1.0;
  EXPECT_THAT(bad.Validate(), HasSubstr("gravity_tolerance_mps2"));
}

TEST(ChiSquareUpperTail, MatchesTableValues) {
  // Critical values of the chi-square distribution (e.g. NIST/SEMATECH
  // e-Handbook 1.3.6.7.4) and their upper-tail probabilities.
  EXPECT_NEAR(ChiSquareUpperTail(3.841458820694124, 1), 0.05, kTableTolerance);
  EXPECT_NEAR(ChiSquareUpperTail(9.210340371976184, 2), 0.01, kTableTolerance);
  EXPECT_NEAR(ChiSquareUpperTail(11.344866730144373, 3), 0.01, kTableTolerance);
  EXPECT_NEAR(ChiSquareUpperTail(13.276704135987622, 4), 0.01, kTableTolerance);
  EXPECT_NEAR(ChiSquareUpperTail(15.086272469388987, 5), 0.01, kTableTolerance);
  EXPECT_NEAR(ChiSquareUpperTail(1.3862943611198906, 2), 0.5, kTableTolerance);
  EXPECT_DOUBLE_EQ(ChiSquareUpperTail(0.0, 1), 1.0);
  EXPECT_DOUBLE_EQ(ChiSquareUpperTail(0.0, 4), 1.0);
  EXPECT_LT(ChiSquareUpperTail(1e4, 3), 1e-300);
}

TEST(Repeatability, PopulationAndSampleStdMatchAHandComputation) {
  // Bias x of 1, 2, 4 m/s²: mean 7/3, squared deviations (16 + 1 + 25)/9 =
  // 14/3, population std √(14/9), sample std √(14/6).
  std::vector<Calibration> trials(3);
  trials[0].model.bias_mps2.x() = 1.0;
  trials[1].model.bias_mps2.x() = 2.0;
  trials[2].model.bias_mps2.x() = 4.0;
  // Scale y of two equal trials and a third: 0.01, 0.01, 0.04: mean 0.02,
  // squared deviations 1e-4 + 1e-4 + 4e-4 = 6e-4.
  trials[0].model.scale_factor_error.y() = 0.01;
  trials[1].model.scale_factor_error.y() = 0.01;
  trials[2].model.scale_factor_error.y() = 0.04;
  const RepeatabilityResult r = AnalyzeRepeatability(trials);
  ASSERT_EQ(r.trials, 3);
  const ParameterRepeatability& bx = r.parameters[0];
  EXPECT_THAT(bx.values, ::testing::ElementsAre(1.0, 2.0, 4.0));
  EXPECT_NEAR(bx.mean, 7.0 / 3.0, kArithmetic);
  EXPECT_NEAR(bx.std_population, std::sqrt(14.0 / 9.0), kArithmetic);
  EXPECT_NEAR(bx.std_sample, std::sqrt(14.0 / 6.0), kArithmetic);
  const ParameterRepeatability& sy = r.parameters[4];
  EXPECT_NEAR(sy.mean, 0.02, kArithmetic);
  EXPECT_NEAR(sy.std_population, std::sqrt(6e-4 / 3.0), kArithmetic);
  EXPECT_NEAR(sy.std_sample, std::sqrt(6e-4 / 2.0), kArithmetic);
  // Parameters equal in every trial have no spread.
  EXPECT_EQ(r.parameters[8].std_population, 0.0);
  EXPECT_EQ(r.parameters[8].std_sample, 0.0);
}

TEST(Repeatability, TwoTrialsSampleStdIsRootTwoTimesPopulation) {
  std::vector<Calibration> trials(2);
  trials[0].model.theta_zx_rad = 1e-3;
  trials[1].model.theta_zx_rad = 2e-3;
  const RepeatabilityResult r = AnalyzeRepeatability(trials);
  EXPECT_NEAR(r.parameters[7].std_population, 0.5e-3, kArithmetic);
  EXPECT_NEAR(r.parameters[7].std_sample, 0.5e-3 * std::sqrt(2.0), kArithmetic);
}

TEST(Repeatability, FlagsTheBiasThatMovedAndNothingElse) {
  const RepeatabilityResult r = AnalyzeRepeatability(BiasMovedInTrial2());
  for (int p = 0; p < kNumModelParameters; ++p) {
    SCOPED_TRACE(std::string(kParameterNames[static_cast<std::size_t>(p)]));
    const ParameterRepeatability& row = r.parameters[static_cast<std::size_t>(p)];
    ASSERT_TRUE(row.changed.has_value()) << row.no_verdict_reason;
    EXPECT_EQ(*row.changed, p == 0);
    EXPECT_TRUE(row.no_verdict_reason.empty());
  }
  EXPECT_DOUBLE_EQ(r.significance, 0.01);
  const std::string verdict = RepeatabilityVerdict(r);
  EXPECT_THAT(verdict, HasSubstr("bias x changed between sessions beyond their 1σ"));
  EXPECT_THAT(verdict, HasSubstr("expected: the bias changes at every power-up"));
  EXPECT_THAT(verdict,
              HasSubstr("bias y, z; scale-factor error x, y, z; "
                        "non-orthogonality yz, zx, zy did not"));
  EXPECT_THAT(verdict, HasSubstr("calibrate scale and non-orthogonality once"));
}

TEST(Repeatability, ChiSquareIsTheWeightedSpreadOverTheTrialSigma) {
  // Bias x offsets 0.5, 30, -0.2 (in σ, equal σ): weighted mean = plain mean
  // 10.1, χ² = 9.6² + 19.9² + 10.3² = 594.26 with 2 degrees of freedom, whose
  // upper tail is exp(-χ²/2).
  const RepeatabilityResult r = AnalyzeRepeatability(BiasMovedInTrial2());
  ASSERT_TRUE(r.parameters[0].chi2.has_value());
  EXPECT_NEAR(*r.parameters[0].chi2, 594.26, 1e-8);
  EXPECT_NEAR(*r.parameters[0].p_value / std::exp(-*r.parameters[0].chi2 / 2.0),
              1.0,
              kArithmetic);
  // Angle zx offsets -0.3, 0.4, -0.6: χ² = Σx² − n·mean² = 0.61 − 3·(1/6)².
  EXPECT_NEAR(*r.parameters[7].chi2, 0.61 - 1.0 / 12.0, 1e-9);
  EXPECT_NEAR(*r.parameters[7].p_value, std::exp(-(0.61 - 1.0 / 12.0) / 2.0), 1e-9);
}

TEST(Repeatability, UnequalSigmaWeightsTheMean) {
  // Values 0 and 3 with σ 1 and 2: weights 1 and 1/4, weighted mean 0.6,
  // χ² = 0.6² + (2.4/2)² = 1.8 (1 dof).
  std::vector<Calibration> trials = {Still(), Still()};
  trials[0].model.bias_mps2.z() = 0.0;
  trials[1].model.bias_mps2.z() = 3.0;
  trials[0].std->bias_mps2.z() = 1.0;
  trials[1].std->bias_mps2.z() = 2.0;
  const RepeatabilityResult r = AnalyzeRepeatability(trials);
  EXPECT_NEAR(*r.parameters[2].chi2, 1.8, kArithmetic);
  EXPECT_NEAR(*r.parameters[2].p_value, std::erfc(std::sqrt(0.9)), kArithmetic);
  EXPECT_FALSE(*r.parameters[2].changed);
}

TEST(Repeatability, SignificanceLevelMovesTheVerdict) {
  // χ² = 1.8 at 1 dof has p = 0.18: not at 1 %, yes at 20 %.
  std::vector<Calibration> trials = {Still(), Still()};
  trials[1].model.bias_mps2.y() += std::sqrt(3.6) * kBiasStd;  // χ² = 3.6/2
  RepeatabilityOptions options;
  EXPECT_FALSE(*AnalyzeRepeatability(trials, options).parameters[1].changed);
  options.significance = 0.2;
  EXPECT_TRUE(*AnalyzeRepeatability(trials, options).parameters[1].changed);
}

TEST(Repeatability, NoSigmaGivesNoVerdictRatherThanAGuess) {
  // Two trials without 1σ: nothing to measure the differences by.
  std::vector<Calibration> trials = BiasMovedInTrial2();
  trials[1].std.reset();
  trials[2].std.reset();
  const std::vector<std::string> names = {"a.json", "b.json", "c.json"};
  const RepeatabilityResult r = AnalyzeRepeatability(trials, names);
  for (const ParameterRepeatability& row : r.parameters) {
    EXPECT_FALSE(row.changed.has_value());
    EXPECT_FALSE(row.chi2.has_value());
    EXPECT_THAT(row.no_verdict_reason,
                AllOf(HasSubstr("no uncertainty given"), HasSubstr("trial 2 (b.json)")));
  }
  // The statistics are there all the same.
  EXPECT_GT(r.parameters[0].std_population, 10 * kBiasStd);
  EXPECT_THAT(RepeatabilityVerdict(r), HasSubstr("no uncertainty given"));
  EXPECT_THAT(RepeatabilityVerdict(r), ::testing::Not(HasSubstr("changed between")));
  ASSERT_FALSE(r.notes.empty());
  EXPECT_THAT(r.notes[0], HasSubstr("trial 2 (b.json), trial 3 (c.json) carry no 1σ"));
}

TEST(Repeatability, OneTrialWithoutSigmaIsTheReferenceOfTheOthers) {
  // An imported calibration (no 1σ) against mpcal's: each other trial's
  // difference from it in units of that trial's own 1σ.
  std::vector<Calibration> trials = BiasMovedInTrial2();
  trials[0].std.reset();
  const std::vector<std::string> names = {"imported.json", "b.json", "c.json"};
  const RepeatabilityResult r = AnalyzeRepeatability(trials, names);
  for (int p = 0; p < kNumModelParameters; ++p) {
    const ParameterRepeatability& row = r.parameters[static_cast<std::size_t>(p)];
    ASSERT_TRUE(row.changed.has_value()) << p;
    ASSERT_EQ(row.reference_trial, std::optional<std::size_t>(0));
    double chi2 = 0.0;
    for (std::size_t i = 1; i < 3; ++i) {
      const double sigma = ToVector(*trials[i].std)[p];
      const double z =
          (ToVector(trials[i].model)[p] - ToVector(trials[0].model)[p]) / sigma;
      EXPECT_NEAR(row.z_from_reference[i], z, 1e-9 * (1.0 + std::abs(z))) << p;
      chi2 += z * z;
    }
    EXPECT_NEAR(*row.chi2, chi2, 1e-9 * (1.0 + chi2)) << p;
    EXPECT_EQ(row.z_from_reference[0], 0.0);
  }
  // Trial 2's bias moved by many 1σ: changed; its scale did not.
  EXPECT_TRUE(*r.parameters[0].changed);
  EXPECT_FALSE(*r.parameters[3].changed);
  ASSERT_FALSE(r.notes.empty());
  EXPECT_THAT(r.notes.back(), HasSubstr("trial 1 (imported.json) carries no 1σ"));
  EXPECT_THAT(r.notes.back(), HasSubstr("compared with it in units of its own 1σ"));
}

TEST(Repeatability, ZeroSigmaGivesNoVerdict) {
  std::vector<Calibration> trials = BiasMovedInTrial2();
  trials[1].std->scale_factor_error.y() = 0.0;
  const RepeatabilityResult r = AnalyzeRepeatability(trials);
  EXPECT_FALSE(r.parameters[4].changed.has_value());
  EXPECT_THAT(r.parameters[4].no_verdict_reason, HasSubstr("zero"));
  EXPECT_TRUE(r.parameters[3].changed.has_value());
}

TEST(Repeatability, SixParameterModelHasNoVerdictOnTheAngles) {
  std::vector<Calibration> trials = BiasMovedInTrial2();
  for (Calibration& c : trials) {
    c.model_kind = ModelKind::kBiasScale6;
    c.model.theta_yz_rad = c.model.theta_zx_rad = c.model.theta_zy_rad = 0.0;
    c.std->theta_yz_rad = c.std->theta_zx_rad = c.std->theta_zy_rad = 0.0;
  }
  const RepeatabilityResult r = AnalyzeRepeatability(trials);
  EXPECT_TRUE(*r.parameters[0].changed);
  for (int p = 6; p < 9; ++p) {
    EXPECT_FALSE(r.parameters[p].changed.has_value());
    EXPECT_THAT(r.parameters[p].no_verdict_reason, HasSubstr("not estimated"));
  }
  // Angles not estimated are neither "no uncertainty" nor a change.
  const std::string verdict = RepeatabilityVerdict(r);
  EXPECT_THAT(verdict, ::testing::Not(HasSubstr("no uncertainty")));
  EXPECT_THAT(verdict, ::testing::Not(HasSubstr("non-orthogonality")));
}

TEST(Repeatability, NothingChangedSaysOneCalibrationHolds) {
  std::vector<Calibration> trials = BiasMovedInTrial2();
  trials[1].model.bias_mps2.x() = trials[0].model.bias_mps2.x();
  const RepeatabilityResult r = AnalyzeRepeatability(trials);
  for (const ParameterRepeatability& row : r.parameters) EXPECT_FALSE(*row.changed);
  EXPECT_THAT(RepeatabilityVerdict(r), HasSubstr("one calibration holds"));
}

TEST(Repeatability, ScaleChangeAdvisesCalibratingBeforeEachUse) {
  std::vector<Calibration> trials = BiasMovedInTrial2();
  trials[2].model.scale_factor_error.z() += 50 * kScaleStd;
  const RepeatabilityResult r = AnalyzeRepeatability(trials);
  EXPECT_TRUE(*r.parameters[5].changed);
  const std::string verdict = RepeatabilityVerdict(r);
  EXPECT_THAT(verdict, HasSubstr("bias x; scale-factor error z changed"));
  EXPECT_THAT(verdict, ::testing::Not(HasSubstr("expected")));
  EXPECT_THAT(verdict, HasSubstr("calibrate before each use"));
}

TEST(Repeatability, FewerThanTwoTrialsIsAnError) {
  std::vector<Calibration> one(1);
  EXPECT_THAT([&] { AnalyzeRepeatability(one); },
              ::testing::ThrowsMessage<Error>(
                  AllOf(HasSubstr("at least 2 trials"), HasSubstr("got 1"))));
  EXPECT_THAT([&] { AnalyzeRepeatability(std::span<const Calibration>()); },
              ::testing::ThrowsMessage<Error>(HasSubstr("got 0")));
}

TEST(Repeatability, RefusesTrialsOfDifferentModels) {
  std::vector<Calibration> trials = BiasMovedInTrial2();
  trials[2].model_kind = ModelKind::kBiasScale6;
  const std::vector<std::string> names = {"a.json", "b.json", "c.csv"};
  EXPECT_THAT([&] { AnalyzeRepeatability(trials, names); },
              ::testing::ThrowsMessage<Error>(AllOf(HasSubstr("trial 3 (c.csv)"),
                                                    HasSubstr("bias-scale-6"),
                                                    HasSubstr("trial 1 (a.json)"),
                                                    HasSubstr("shin-el-sheimy-9"),
                                                    HasSubstr("share one model"))));
  try {
    AnalyzeRepeatability(trials, names);
  } catch (const Error& e) {
    // Calibrate every session with the same model: a fact, spelled by the command.
    ASSERT_EQ(e.advice().settings.size(), 1u);
    EXPECT_EQ(e.advice().settings[0].option, Option::kModel);
    EXPECT_EQ(e.advice().stage, Stage::kCalibrate);
  }
}

TEST(Repeatability, RefusesTrialsOfDifferentGravity) {
  std::vector<Calibration> trials = BiasMovedInTrial2();
  trials[1].gravity_mps2 = 9.7803;
  EXPECT_THAT([&] { AnalyzeRepeatability(trials); },
              ::testing::ThrowsMessage<Error>(
                  AllOf(HasSubstr("trial 2 was calibrated against gravity 9.7803"),
                        HasSubstr("9.80665"),
                        HasSubstr("do not compare"))));
  try {
    AnalyzeRepeatability(trials);
  } catch (const Error& e) {
    // The same gravity, or the site's latitude and height: facts the
    // command spells as its flags.
    ASSERT_FALSE(e.advice().settings.empty());
    EXPECT_EQ(e.advice().settings[0].option, Option::kGravity);
    EXPECT_EQ(e.advice().stage, Stage::kCalibrate);
  }
  // Rounding in a file is not a different gravity.
  trials[1].gravity_mps2 = 9.80665 + 1e-12;
  EXPECT_NO_THROW(AnalyzeRepeatability(trials));
}

TEST(Repeatability, RefusesTrialsOfDifferentUnits) {
  std::vector<Calibration> trials = BiasMovedInTrial2();
  trials[1].input_units = AccelUnits::kG;
  trials[1].mps2_per_unit = kStandardGravityMps2;
  EXPECT_THAT(
      [&] { AnalyzeRepeatability(trials); },
      ::testing::ThrowsMessage<Error>(AllOf(HasSubstr("trial 2 is for input units g"),
                                            HasSubstr("mps2"),
                                            HasSubstr("share the units"))));
  try {
    AnalyzeRepeatability(trials);
  } catch (const Error& e) {
    ASSERT_EQ(e.advice().settings.size(), 1u);
    EXPECT_EQ(e.advice().settings[0].option, Option::kLogUnits);
    EXPECT_EQ(e.advice().settings[0].value, "mps2");
  }
}

TEST(Repeatability, RefusesNonFiniteValuesAndWrongNameCount) {
  std::vector<Calibration> trials = BiasMovedInTrial2();
  trials[1].std->theta_zy_rad = std::nan("");
  EXPECT_THAT([&] { AnalyzeRepeatability(trials); },
              ::testing::ThrowsMessage<Error>(HasSubstr("trial 2 has a non-finite")));
  trials = BiasMovedInTrial2();
  const std::vector<std::string> two = {"a", "b"};
  EXPECT_THROW(AnalyzeRepeatability(trials, two), Error);
  RepeatabilityOptions bad;
  bad.significance = 0.0;
  EXPECT_THAT([&] { AnalyzeRepeatability(trials, bad); },
              ::testing::ThrowsMessage<Error>(HasSubstr("significance")));
}

TEST(Repeatability, CountsTrialsAreComparedOnOneNominalFactor) {
  // The same sensor, raw counts, nominal factor found separately per session:
  // trial 2 holds the identical correction written for a 1 % larger factor.
  std::vector<Calibration> trials = BiasMovedInTrial2();
  trials[1] = trials[0];
  for (Calibration& c : trials) {
    c.input_units = AccelUnits::kCounts;
    c.mps2_per_unit = 1.0 / 400.0;
  }
  const double k = 1.01;
  trials[1].mps2_per_unit *= k;
  trials[1].model.bias_mps2 *= k;
  trials[1].model.scale_factor_error =
      (Eigen::Vector3d::Ones() + trials[1].model.scale_factor_error) * k -
      Eigen::Vector3d::Ones();
  trials[1].std->bias_mps2 *= k;
  trials[1].std->scale_factor_error *= k;
  // Same correction of the same raw reading.
  const Eigen::Vector3d raw(33000.0, 31000.0, 36000.0);
  ASSERT_LT((trials[0].Correct(raw) - trials[1].Correct(raw)).norm(), 1e-9);

  const RepeatabilityResult r = AnalyzeRepeatability(trials);
  for (int p = 0; p < kNumModelParameters; ++p) {
    const ParameterRepeatability& row = r.parameters[static_cast<std::size_t>(p)];
    EXPECT_NEAR(row.values[1], row.values[0], 1e-12) << kParameterNames[p];
  }
  EXPECT_DOUBLE_EQ(r.mps2_per_unit, 1.0 / 400.0);
  ASSERT_EQ(r.notes.size(), 1u);
  EXPECT_THAT(r.notes[0], HasSubstr("re-expressed"));
}

}  // namespace
}  // namespace mpcal
