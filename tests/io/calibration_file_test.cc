#include "mpcal/calibration_file.h"

#include <cmath>
#include <limits>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "mpcal/error.h"
#include "test_util.h"

namespace mpcal {
namespace {

using mpcal::testing::ScratchDir;
using ::testing::AllOf;
using ::testing::HasSubstr;

// Doubles are written with 17 significant digits: reading them back is
// exact, far inside the 1e-15 relative the format promises.
constexpr double kRoundTripRelative = 1e-15;

Calibration FullCalibration() {
  Calibration c;
  c.model_kind = ModelKind::kShinElSheimy9;
  c.gravity_mps2 = 9.81744;
  c.input_units = AccelUnits::kCounts;
  c.mps2_per_unit = 1.0 / 3277.1234567;
  c.model.bias_mps2 = {0.1236, 0.1078, -0.1365};
  c.model.scale_factor_error = {-0.0019998, -0.0009909, 0.0009957};
  c.model.theta_yz_rad = 1.0e-5;
  c.model.theta_zx_rad = 1.8e-4;
  c.model.theta_zy_rad = -1.7e-4 / 3.0;
  ErrorModel s;
  s.bias_mps2 = {1e-4, 2e-4, 3e-4};
  s.scale_factor_error = {1e-5, 2e-5, 3e-5};
  s.theta_yz_rad = 1e-5;
  s.theta_zx_rad = 2e-5;
  s.theta_zy_rad = 3e-5;
  c.std = s;
  FitSummary fit;
  fit.positions = 26;
  fit.residual_rms_before_mps2 = 0.123456789;
  fit.residual_rms_after_mps2 = 0.000987654321;
  fit.iterations = 7;
  fit.converged = true;
  fit.excluded_positions = 1;
  fit.variance_factor = 1.0123;
  fit.cross_validation_rms_mps2 = 0.00111;
  c.fit = fit;
  PositionSummary p;
  p.start_s = 10.5;
  p.end_s = 20.25;
  p.samples = 975;
  p.mean_mps2 = {0.1, -0.2, 9.81};
  p.sample_std_mps2 = {0.01, 0.02, 0.03};
  p.residual_before_mps2 = 0.05;
  p.residual_after_mps2 = -0.0004;
  p.cross_validation_residual_mps2 = 0.0006;
  c.positions.push_back(p);
  p.used = false;
  p.cross_validation_residual_mps2.reset();
  c.positions.push_back(p);
  c.warnings = {"theta_zx_rad is poorly determined", "position 2 excluded"};
  c.provenance = Provenance{"0.1.0", "session.csv", "--units counts --gravity 9.81744"};
  return c;
}

void ExpectNear(double a, double b, const std::string& what) {
  EXPECT_LE(std::abs(a - b), kRoundTripRelative * std::abs(b)) << what;
}

void ExpectModelsEqual(const ErrorModel& a, const ErrorModel& b) {
  const auto va = ToVector(a);
  const auto vb = ToVector(b);
  for (int i = 0; i < kNumModelParameters; ++i)
    ExpectNear(va[i], vb[i], std::string(kParameterNames[i]));
}

std::string FromJsonError(const std::string& text) {
  try {
    CalibrationFromJson(text, "calib.json");
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error for " << text;
  return "";
}

// A valid file as JSON, to break one field at a time.
nlohmann::json ValidJson() {
  return nlohmann::json::parse(CalibrationToJson(FullCalibration()));
}

TEST(CalibrationFile, RoundTripIsExact) {
  const Calibration c = FullCalibration();
  const Calibration r = CalibrationFromJson(CalibrationToJson(c), "test");
  EXPECT_EQ(r.model_kind, c.model_kind);
  ExpectNear(r.gravity_mps2, c.gravity_mps2, "gravity");
  EXPECT_EQ(r.input_units, c.input_units);
  ExpectNear(r.mps2_per_unit, c.mps2_per_unit, "mps2_per_unit");
  ExpectModelsEqual(r.model, c.model);
  ASSERT_TRUE(r.std.has_value());
  ExpectModelsEqual(*r.std, *c.std);
  ASSERT_TRUE(r.fit.has_value());
  EXPECT_EQ(r.fit->positions, 26);
  EXPECT_EQ(r.fit->iterations, 7);
  EXPECT_TRUE(r.fit->converged);
  EXPECT_EQ(r.fit->excluded_positions, 1);
  ExpectNear(r.fit->residual_rms_before_mps2, c.fit->residual_rms_before_mps2, "before");
  ExpectNear(r.fit->residual_rms_after_mps2, c.fit->residual_rms_after_mps2, "after");
  ExpectNear(*r.fit->variance_factor, *c.fit->variance_factor, "variance_factor");
  ExpectNear(*r.fit->cross_validation_rms_mps2, *c.fit->cross_validation_rms_mps2, "cv");
  ASSERT_EQ(r.positions.size(), 2u);
  for (std::size_t i = 0; i < 2; ++i) {
    const PositionSummary& a = r.positions[i];
    const PositionSummary& b = c.positions[i];
    ExpectNear(a.start_s, b.start_s, "start_s");
    ExpectNear(a.end_s, b.end_s, "end_s");
    EXPECT_EQ(a.samples, b.samples);
    for (int k = 0; k < 3; ++k) {
      ExpectNear(a.mean_mps2[k], b.mean_mps2[k], "mean");
      ExpectNear(a.sample_std_mps2[k], b.sample_std_mps2[k], "std");
    }
    ExpectNear(a.residual_before_mps2, b.residual_before_mps2, "residual_before");
    ExpectNear(a.residual_after_mps2, b.residual_after_mps2, "residual_after");
    EXPECT_EQ(a.cross_validation_residual_mps2.has_value(),
              b.cross_validation_residual_mps2.has_value());
    EXPECT_EQ(a.used, b.used);
  }
  EXPECT_EQ(r.warnings, c.warnings);
  ASSERT_TRUE(r.provenance.has_value());
  EXPECT_EQ(r.provenance->options, c.provenance->options);
  EXPECT_EQ(r.provenance->input, "session.csv");
}

TEST(CalibrationFile, SplitHalfCheckRoundTrips) {
  Calibration c = FullCalibration();
  SplitHalfSummary check;
  check.widening = 1.7;
  SplitHalfComparison by_time;
  by_time.kind = SplitKind::kByTime;
  by_time.positions_first = 13;
  by_time.positions_second = 13;
  by_time.determined = true;
  by_time.z = {0.1, -2.5, 3.0, 0.4, -0.5, 0.6, -0.7, 0.8, -0.9};
  by_time.rms_z = 1.4;
  by_time.chi2 = 26.0;
  by_time.dof = 9;
  by_time.p_value = 0.002;
  by_time.disagree = true;
  SplitHalfComparison alternate;
  alternate.kind = SplitKind::kInterleaved;
  alternate.positions_first = 13;
  alternate.positions_second = 13;
  check.comparisons = {by_time, alternate};
  c.fit->split_half = check;
  const Calibration r = CalibrationFromJson(CalibrationToJson(c), "test");
  ASSERT_TRUE(r.fit->split_half.has_value());
  const SplitHalfSummary& back = *r.fit->split_half;
  EXPECT_EQ(back.widening, 1.7);
  EXPECT_EQ(back.significance, 0.01);
  ASSERT_EQ(back.comparisons.size(), 2u);
  EXPECT_EQ(back.comparisons[0].z, by_time.z);
  EXPECT_EQ(back.comparisons[0].dof, 9);
  EXPECT_TRUE(back.comparisons[0].disagree);
  EXPECT_EQ(back.comparisons[0].p_value, 0.002);
  EXPECT_EQ(back.comparisons[1].kind, SplitKind::kInterleaved);
  EXPECT_FALSE(back.comparisons[1].determined);
  const nlohmann::json j = nlohmann::json::parse(CalibrationToJson(c));
  EXPECT_EQ(j["fit"]["split_half"]["by_time"]["rms_z"], 1.4);
  // A widening below 1 would shrink the 1σ: refused.
  nlohmann::json bad = j;
  bad["fit"]["split_half"]["widening"] = 0.5;
  EXPECT_THAT(FromJsonError(bad.dump()), HasSubstr("fit.split_half.widening"));
}

TEST(CalibrationFile, BiasDriftRoundTrips) {
  Calibration c = FullCalibration();
  BiasDrift drift;
  drift.mps2_per_s = {2e-5, -1e-5, 3e-5};
  drift.std_mps2_per_s = {1e-6, 2e-6, 3e-6};
  drift.reference_time_s = 151.25;
  drift.p_value = 1e-4;
  c.bias_drift = drift;
  const nlohmann::json j = nlohmann::json::parse(CalibrationToJson(c));
  EXPECT_EQ(j["bias_drift_mps2_per_s"][1], -1e-5);
  EXPECT_EQ(j["bias_reference_time_s"], 151.25);
  EXPECT_EQ(j["std"]["bias_drift_mps2_per_s"][2], 3e-6);
  const Calibration r = CalibrationFromJson(j.dump(), "test");
  ASSERT_TRUE(r.bias_drift.has_value());
  EXPECT_EQ(r.bias_drift->mps2_per_s, drift.mps2_per_s);
  EXPECT_EQ(r.bias_drift->std_mps2_per_s, drift.std_mps2_per_s);
  EXPECT_EQ(r.bias_drift->reference_time_s, 151.25);
  EXPECT_EQ(r.bias_drift->p_value, 1e-4);
  // Without the drift fields there is no drift.
  EXPECT_FALSE(CalibrationFromJson(CalibrationToJson(FullCalibration()), "t").bias_drift);
}

TEST(CalibrationFile, TruthFileWithoutOptionalPartsRoundTrips) {
  Calibration c;
  c.input_units = AccelUnits::kG;
  c.mps2_per_unit = kStandardGravityMps2;
  c.model.bias_mps2 = {0.01, 0.02, 0.03};
  c.model_kind = ModelKind::kBiasScale6;
  const Calibration r = CalibrationFromJson(CalibrationToJson(c), "truth");
  EXPECT_FALSE(r.std.has_value());
  EXPECT_FALSE(r.fit.has_value());
  EXPECT_FALSE(r.provenance.has_value());
  EXPECT_TRUE(r.positions.empty());
  EXPECT_EQ(r.model_kind, ModelKind::kBiasScale6);
  ExpectModelsEqual(r.model, c.model);
}

TEST(CalibrationFile, HasTheDocumentedSchema) {
  const nlohmann::json j = ValidJson();
  EXPECT_EQ(j["format"], "mpcal.accelerometer/1");
  EXPECT_EQ(j["model"], "shin-el-sheimy-9");
  EXPECT_EQ(j["input"]["units"], "counts");
  EXPECT_EQ(j["bias_mps2"].size(), 3u);
  EXPECT_TRUE(j["non_orthogonality_rad"].contains("zx"));
  EXPECT_TRUE(j["std"].contains("scale_factor_error"));
  EXPECT_EQ(j["fit"]["positions"], 26);
  EXPECT_EQ(j["positions"][0]["samples"], 975);
  EXPECT_EQ(j["provenance"]["input"], "session.csv");
}

TEST(CalibrationFile, WriteAndReadBackFromDisk) {
  ScratchDir dir;
  const std::string path = dir.Path("calib.json");
  WriteCalibrationFile(path, FullCalibration());
  const Calibration r = ReadCalibrationFile(path);
  ExpectModelsEqual(r.model, FullCalibration().model);
}

TEST(CalibrationFile, WriterRefusesNonFiniteValues) {
  Calibration c = FullCalibration();
  c.model.bias_mps2.y() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(
      {
        try {
          CalibrationToJson(c);
        } catch (const Error& e) {
          EXPECT_THAT(e.what(), HasSubstr("bias_mps2"));
          throw;
        }
      },
      Error);
}

TEST(CalibrationFile, MalformedJsonGivesLineAndColumn) {
  EXPECT_THAT(
      FromJsonError("{\n  \"format\": \"mpcal.accelerometer/1\",\n  oops\n}"),
      AllOf(HasSubstr("calib.json"), HasSubstr("not valid JSON"), HasSubstr("line 3")));
  EXPECT_THAT(FromJsonError(""), HasSubstr("empty"));
  EXPECT_THAT(FromJsonError("[1, 2]"), HasSubstr("expected a JSON object"));
}

TEST(CalibrationFile, FormatAndVersion) {
  nlohmann::json j = ValidJson();
  j.erase("format");
  EXPECT_THAT(FromJsonError(j.dump()), HasSubstr("no 'format' field"));
  try {
    CalibrationFromJson(j.dump(), "calib.json");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    // The command line adds "expected JSON written by 'mpcal calibrate'".
    EXPECT_EQ(e.kind(), ErrorKind::kFormat);
    EXPECT_EQ(e.advice().stage, Stage::kCalibrate);
  }
  j["format"] = "mpcal.gyroscope/1";
  EXPECT_THAT(FromJsonError(j.dump()),
              HasSubstr("format 'mpcal.gyroscope/1' is not 'mpcal.accelerometer/1'"));
  j["format"] = "mpcal.accelerometer/2";
  EXPECT_THAT(FromJsonError(j.dump()),
              AllOf(HasSubstr("version 2"), HasSubstr("this mpcal reads version 1")));
  j["format"] = 1;
  EXPECT_THAT(FromJsonError(j.dump()), HasSubstr("'format' must be a string"));
  // A minor revision of version 1 is read.
  j["format"] = "mpcal.accelerometer/1.3";
  EXPECT_NO_THROW(CalibrationFromJson(j.dump(), "calib.json"));
}

TEST(CalibrationFile, MissingAndWronglyTypedFieldsAreNamed) {
  for (const char* field : {"model",
                            "gravity_mps2",
                            "input",
                            "bias_mps2",
                            "scale_factor_error",
                            "non_orthogonality_rad"}) {
    nlohmann::json j = ValidJson();
    j.erase(field);
    EXPECT_THAT(FromJsonError(j.dump()),
                HasSubstr(std::string("missing field '") + field + "'"));
  }
  nlohmann::json j = ValidJson();
  j["non_orthogonality_rad"].erase("zy");
  EXPECT_THAT(FromJsonError(j.dump()), HasSubstr("'non_orthogonality_rad.zy'"));
  j = ValidJson();
  j["fit"]["iterations"] = "seven";
  EXPECT_THAT(
      FromJsonError(j.dump()),
      AllOf(HasSubstr("'fit.iterations'"), HasSubstr("integer"), HasSubstr("a string")));
  j = ValidJson();
  j["bias_mps2"] = {1, 2};
  EXPECT_THAT(FromJsonError(j.dump()),
              AllOf(HasSubstr("'bias_mps2'"), HasSubstr("2 elements")));
  j = ValidJson();
  j["std"]["bias_mps2"][1] = "x";
  EXPECT_THAT(FromJsonError(j.dump()), HasSubstr("'std.bias_mps2[1]'"));
  j = ValidJson();
  j["positions"][1]["mean_mps2"] = nullptr;
  EXPECT_THAT(FromJsonError(j.dump()), HasSubstr("'positions[1].mean_mps2'"));
  j = ValidJson();
  j["input"]["mps2_per_unit"] = nullptr;
  EXPECT_THAT(FromJsonError(j.dump()),
              AllOf(HasSubstr("'input.mps2_per_unit'"), HasSubstr("null")));
}

TEST(CalibrationFile, UnknownModelAndUnits) {
  nlohmann::json j = ValidJson();
  j["model"] = "twelve-parameter";
  EXPECT_THAT(
      FromJsonError(j.dump()),
      AllOf(HasSubstr("unknown model 'twelve-parameter'"), HasSubstr("bias-scale-6")));
  j = ValidJson();
  j["input"]["units"] = "furlongs";
  EXPECT_THAT(FromJsonError(j.dump()), HasSubstr("unknown units 'furlongs'"));
}

TEST(CalibrationFile, ImplausibleValues) {
  nlohmann::json j = ValidJson();
  j["input"]["mps2_per_unit"] = 0.0;
  EXPECT_THAT(FromJsonError(j.dump()), HasSubstr("is not a sensor's scale"));
  j["input"]["mps2_per_unit"] = -1.0;
  EXPECT_THAT(FromJsonError(j.dump()), HasSubstr("is not a sensor's scale"));
  j = ValidJson();
  j["input"] = {{"units", "g"}, {"mps2_per_unit", 1.0}};
  EXPECT_THAT(FromJsonError(j.dump()), HasSubstr("9.80665"));
  j = ValidJson();
  j["gravity_mps2"] = 1.0;
  EXPECT_THAT(FromJsonError(j.dump()), HasSubstr("gravity_mps2"));
  j = ValidJson();
  j["scale_factor_error"][0] = -1.0;
  EXPECT_THAT(FromJsonError(j.dump()), HasSubstr("scale_factor_error[0]"));
  j = ValidJson();
  j["non_orthogonality_rad"]["yz"] = 1.6;
  EXPECT_THAT(FromJsonError(j.dump()), HasSubstr("non_orthogonality_rad.yz"));
  j = ValidJson();
  j["std"]["scale_factor_error"][2] = -1e-5;
  EXPECT_THAT(FromJsonError(j.dump()), HasSubstr("negative standard deviation"));
  j = ValidJson();
  j["model"] = "bias-scale-6";
  EXPECT_THAT(FromJsonError(j.dump()), HasSubstr("no non-orthogonality"));
}

TEST(CalibrationFile, NonFiniteNumbersInTheText) {
  // JSON has no NaN or infinity: nlohmann rejects the literals and numbers
  // that overflow a double.
  std::string text = CalibrationToJson(FullCalibration());
  const auto pos = text.find("9.81744");
  ASSERT_NE(pos, std::string::npos);
  EXPECT_THAT(FromJsonError(text.substr(0, pos) + "NaN" + text.substr(pos + 7)),
              HasSubstr("not valid JSON"));
  EXPECT_THAT(FromJsonError(text.substr(0, pos) + "1e999" + text.substr(pos + 7)),
              AllOf(HasSubstr("not valid JSON"), HasSubstr("1e999")));
}

TEST(CalibrationFile, UnreadableFiles) {
  ScratchDir dir;
  EXPECT_THROW(ReadCalibrationFile(dir.Path("missing.json")), Error);
  EXPECT_THROW(ReadCalibrationFile(dir.path().string()), Error);
  EXPECT_THROW(ReadCalibrationFile(dir.Write("empty.json", "")), Error);
}

}  // namespace
}  // namespace mpcal
