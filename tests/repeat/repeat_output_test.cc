// The repeatability table's outputs: JSON (and reading it back), CSV and the
// printed table in the paper's units.
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "mpcal/error.h"
#include "mpcal/plausible.h"
#include "mpcal/repeat.h"
#include "mpcal/repeatability_file.h"

namespace mpcal {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

// Three sessions: bias x moved a lot, the rest within σ; trial 3 z's bias
// carries the largest value. Values in SI.
std::vector<Calibration> ThreeTrials(bool with_std) {
  std::vector<Calibration> trials(3);
  const double bias_x[] = {-0.686, -0.501, -0.638};
  for (int t = 0; t < 3; ++t) {
    Calibration& c = trials[static_cast<std::size_t>(t)];
    c.model.bias_mps2 = {bias_x[t], 0.3 + 1e-5 * t, 0.58 - 2e-5 * t};
    c.model.scale_factor_error = {
        -1.998e-3 + 1e-7 * t, -1.0116e-3, -1.0064e-3 - 1e-7 * t};
    c.model.theta_yz_rad = 1.8e-4;
    c.model.theta_zx_rad = 1.82e-3 + 1e-6 * t;
    c.model.theta_zy_rad = 1.67e-3;
    if (with_std) {
      ErrorModel s;
      s.bias_mps2.setConstant(1e-4);
      s.scale_factor_error.setConstant(2e-6);
      s.theta_yz_rad = s.theta_zx_rad = s.theta_zy_rad = 1e-5;
      c.std = s;
    }
  }
  return trials;
}

TEST(RepeatabilityJson, HasTheLayoutOfTheIssue) {
  const RepeatabilityResult r = AnalyzeRepeatability(ThreeTrials(true));
  const std::string text = RepeatabilityToJson(r);
  ASSERT_FALSE(text.empty());
  EXPECT_EQ(text.back(), '\n');
  const nlohmann::json j = nlohmann::json::parse(text);
  EXPECT_EQ(j["format"], "mpcal.repeatability/1");
  EXPECT_EQ(j["trials"], 3);
  const auto& bias = j["parameters"]["bias_mps2"];
  ASSERT_EQ(bias["values"].size(), 3u);
  EXPECT_EQ(bias["values"][1][0].get<double>(), -0.501);
  EXPECT_EQ(bias["values"][2][2].get<double>(), 0.58 - 4e-5);
  EXPECT_EQ(bias["mean"][0].get<double>(), r.parameters[0].mean);
  EXPECT_EQ(bias["std_population"][0].get<double>(), r.parameters[0].std_population);
  EXPECT_EQ(bias["std_sample"][0].get<double>(), r.parameters[0].std_sample);
  EXPECT_EQ(bias["changed"], nlohmann::json::parse("[true, false, false]"));
  const auto& scale = j["parameters"]["scale_factor_error"];
  EXPECT_EQ(scale["values"][1][0].get<double>(), -1.998e-3 + 1e-7);
  EXPECT_EQ(scale["changed"].size(), 3u);
  const auto& zx = j["parameters"]["non_orthogonality_rad"]["zx"];
  EXPECT_EQ(zx["values"].size(), 3u);
  EXPECT_EQ(zx["values"][2].get<double>(), 1.82e-3 + 2e-6);
  EXPECT_TRUE(zx["mean"].is_number());
  EXPECT_TRUE(zx["changed"].is_boolean());
  // The issue's key order, so that a person reading the file finds it.
  EXPECT_LT(text.find("\"format\""), text.find("\"trials\""));
  EXPECT_LT(text.find("\"bias_mps2\""), text.find("\"scale_factor_error\""));
  EXPECT_LT(text.find("\"values\""), text.find("\"mean\""));
}

TEST(RepeatabilityJson, NoVerdictIsNull) {
  const nlohmann::json j = nlohmann::json::parse(
      RepeatabilityToJson(AnalyzeRepeatability(ThreeTrials(false))));
  EXPECT_EQ(j["parameters"]["bias_mps2"]["changed"],
            nlohmann::json::parse("[null,null,null]"));
  EXPECT_TRUE(j["parameters"]["non_orthogonality_rad"]["yz"]["changed"].is_null());
}

TEST(RepeatabilityJson, RoundTripsThroughTheReader) {
  for (bool with_std : {true, false}) {
    const RepeatabilityResult r = AnalyzeRepeatability(ThreeTrials(with_std));
    const RepeatabilityResult back =
        RepeatabilityFromJson(RepeatabilityToJson(r), "mem.json");
    EXPECT_EQ(back.trials, 3);
    EXPECT_THAT(back.trial_names,
                ::testing::ElementsAre("trial 1", "trial 2", "trial 3"));
    for (int p = 0; p < kNumModelParameters; ++p) {
      SCOPED_TRACE(std::string(kParameterNames[static_cast<std::size_t>(p)]));
      const ParameterRepeatability& a = r.parameters[static_cast<std::size_t>(p)];
      const ParameterRepeatability& b = back.parameters[static_cast<std::size_t>(p)];
      // Exact: the writer prints the shortest text that reads back the same.
      EXPECT_EQ(b.values, a.values);
      EXPECT_EQ(b.mean, a.mean);
      EXPECT_EQ(b.std_population, a.std_population);
      EXPECT_EQ(b.std_sample, a.std_sample);
      EXPECT_EQ(b.changed, a.changed);
      EXPECT_FALSE(b.chi2.has_value());
    }
    // And the text of the round trip is the same text.
    EXPECT_EQ(RepeatabilityToJson(back), RepeatabilityToJson(r));
  }
}

std::string ValidJson() {
  return RepeatabilityToJson(AnalyzeRepeatability(ThreeTrials(true)));
}

void ExpectReaderError(const std::string& text, const std::vector<std::string>& parts) {
  try {
    RepeatabilityFromJson(text, "table.json");
    ADD_FAILURE() << "no error for: " << text.substr(0, 200);
  } catch (const Error& e) {
    const std::string what = e.what();
    EXPECT_THAT(what, HasSubstr("table.json: "));
    for (const std::string& part : parts) EXPECT_THAT(what, HasSubstr(part));
  }
}

TEST(RepeatabilityJson, ReaderRejectsBadInputNamingTheField) {
  ExpectReaderError("", {"the file is empty"});
  ExpectReaderError("{\"format\": ", {"not valid JSON"});
  ExpectReaderError("[1, 2]", {"expected a JSON object", "found an array"});
  nlohmann::json j = nlohmann::json::parse(ValidJson());

  nlohmann::json bad = j;
  bad["format"] = "mpcal.accelerometer/1";
  ExpectReaderError(bad.dump(),
                    {"format 'mpcal.accelerometer/1' is not 'mpcal.repeatability/1'"});
  bad = j;
  bad["format"] = "mpcal.repeatability/2";
  ExpectReaderError(bad.dump(),
                    {"is version 2 of the format; this mpcal reads version 1"});
  bad = j;
  bad.erase("trials");
  ExpectReaderError(bad.dump(), {"missing field 'trials'"});
  bad = j;
  bad["trials"] = 1;
  ExpectReaderError(bad.dump(), {"trials", "at least 2"});
  bad = j;
  bad["trials"] = 4;
  ExpectReaderError(
      bad.dump(),
      {"field 'parameters.bias_mps2.values' must be an array of 4 entries, found 3"});
  bad = j;
  bad["parameters"]["bias_mps2"]["values"][1][2] = "0.1";
  ExpectReaderError(
      bad.dump(),
      {"field 'parameters.bias_mps2.values[1][2]' must be a number, found a string"});
  bad = j;
  bad["parameters"]["scale_factor_error"]["std_sample"] = {1.0, 2.0};
  ExpectReaderError(
      bad.dump(),
      {"field 'parameters.scale_factor_error.std_sample' must be an array of 3 entries"});
  bad = j;
  bad["parameters"]["non_orthogonality_rad"].erase("zy");
  ExpectReaderError(bad.dump(), {"missing field 'parameters.non_orthogonality_rad.zy'"});
  bad = j;
  bad["parameters"]["non_orthogonality_rad"]["yz"]["changed"] = "yes";
  ExpectReaderError(
      bad.dump(), {"parameters.non_orthogonality_rad.yz.changed", "true, false or null"});
  // A value too large for a double.
  std::string text = j.dump();
  const std::string key = "\"mean\":";
  text.replace(text.find(key) + key.size(), 0, "[1e999,0,0],\"x\":");
  ExpectReaderError(text, {"not valid JSON", "1e999"});
}

// Absurd but finite values are refused as the calibration file reader
// refuses them (plausible.h): a bias of 1e308 printed inf in the report.
TEST(RepeatabilityJson, ReaderRefusesValuesNoSensorHas) {
  const nlohmann::json j = nlohmann::json::parse(ValidJson());
  nlohmann::json bad = j;
  bad["parameters"]["bias_mps2"]["values"][1][0] = 1e308;
  ExpectReaderError(bad.dump(),
                    {"'parameters.bias_mps2.values[1][0]' = 1e+308 is beyond any "
                     "accelerometer's bias (±98.0665 m/s²)"});
  bad = j;
  bad["parameters"]["bias_mps2"]["mean"][2] = -1e308;
  ExpectReaderError(bad.dump(), {"'parameters.bias_mps2.mean[2]' = -1e+308 is beyond"});
  bad = j;
  bad["parameters"]["bias_mps2"]["std_population"][0] = 1e308;
  ExpectReaderError(bad.dump(),
                    {"'parameters.bias_mps2.std_population[0]' = 1e+308 is not the "
                     "spread of any accelerometer's bias (0 to 196.133 m/s²)"});
  bad = j;
  bad["parameters"]["scale_factor_error"]["std_sample"][1] = -0.001;
  ExpectReaderError(bad.dump(),
                    {"'parameters.scale_factor_error.std_sample[1]' = -0.001 is not the "
                     "spread of any scale-factor error (0 to 1)"});
  bad = j;
  bad["parameters"]["scale_factor_error"]["values"][0][1] = 0.7;
  ExpectReaderError(bad.dump(),
                    {"'parameters.scale_factor_error.values[0][1]' = 0.7 is beyond any "
                     "scale-factor error (±0.5)"});
  bad = j;
  bad["parameters"]["non_orthogonality_rad"]["zx"]["values"][2] = 3.0;
  ExpectReaderError(bad.dump(),
                    {"'parameters.non_orthogonality_rad.zx.values[2]' = 3 is beyond any "
                     "non-orthogonality angle (±0.785398 rad)"});
  bad = j;
  bad["parameters"]["non_orthogonality_rad"]["zy"]["std_sample"] = 1e300;
  ExpectReaderError(bad.dump(),
                    {"'parameters.non_orthogonality_rad.zy.std_sample' = 1e+300 is not"});
  // The limits themselves are values a sensor may have.
  bad = j;
  bad["parameters"]["bias_mps2"]["values"][0][0] = kMaxBiasMps2;
  EXPECT_NO_THROW(RepeatabilityFromJson(bad.dump(), "table.json"));
}

TEST(RepeatabilityCsv, OneRowPerParameterInSi) {
  const RepeatabilityResult r = AnalyzeRepeatability(ThreeTrials(true));
  const std::string csv = RepeatabilityToCsv(r);
  std::istringstream in(csv);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);) lines.push_back(line);
  ASSERT_EQ(lines.size(), 1u + kNumModelParameters);
  EXPECT_EQ(
      lines[0],
      "parameter,trial_1,trial_2,trial_3,mean,std_population,std_sample,changed,chi2,"
      "p_value");
  EXPECT_THAT(lines[1], ::testing::StartsWith("bias_x_mps2,-0.686,-0.501,-0.638,"));
  EXPECT_THAT(lines[1], HasSubstr(",true,"));
  EXPECT_THAT(lines[9], ::testing::StartsWith("theta_zy_rad,0.00167,0.00167,0.00167,"));
  EXPECT_THAT(lines[9], HasSubstr(",false,"));
  const std::string no_std = RepeatabilityToCsv(AnalyzeRepeatability(ThreeTrials(false)));
  EXPECT_THAT(no_std, ::testing::EndsWith(",,,\n"));
}

TEST(RepeatabilityTable, PrintsTheTrialsMeanAndBothDeviationsInTheTableUnits) {
  const std::vector<std::string> names = {"mon.csv", "tue.csv", "wed.json"};
  const RepeatabilityResult r = AnalyzeRepeatability(ThreeTrials(true), names);
  const std::string table = FormatRepeatabilityTable(r);
  EXPECT_THAT(table,
              AllOf(HasSubstr("trial 1: mon.csv"),
                    HasSubstr("trial 3: wed.json"),
                    HasSubstr("std (n)"),
                    HasSubstr("std (n-1)"),
                    HasSubstr("mean"),
                    HasSubstr("desvio")));
  // Bias in mg (3 decimals), scale in ppm, angles in mrad: the README's
  // conventions, as in every other table.
  EXPECT_THAT(table,
              HasSubstr(fmt::format(" {:.3f} ", -0.686 / kStandardGravityMps2 * 1e3)));
  EXPECT_THAT(table, HasSubstr("-1998.00"));
  EXPECT_THAT(table, HasSubstr(" 1.820 "));
  std::istringstream in(table);
  std::string bias_x;
  for (std::string line; std::getline(in, line);) {
    if (line.rfind("bias x", 0) == 0) bias_x = line;
  }
  EXPECT_THAT(bias_x, AllOf(HasSubstr(" mg "), HasSubstr("CHANGED")));
  // Population std of bias x, in mg, to 4 digits.
  EXPECT_THAT(
      bias_x,
      HasSubstr(fmt::format(
          " {:.4g} ", r.parameters[0].std_population / kStandardGravityMps2 * 1e3)));
  std::string theta_yz;
  for (std::istringstream again(table); std::getline(again, theta_yz);) {
    if (theta_yz.rfind("non-orth. yz", 0) == 0) break;
  }
  EXPECT_THAT(theta_yz, HasSubstr(" mrad "));
}

}  // namespace
}  // namespace mpcal
