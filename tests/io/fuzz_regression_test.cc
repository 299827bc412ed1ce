// What the fuzzers (fuzz/) found, kept as regression tests, and a replay of
// their seed corpora (tests/fuzz/<target>/): every input is read cleanly or
// rejected with mpcal::Error, never with another exception or a crash (the
// sanitizer build, `make test-sanitize`, runs this too).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "../../fuzz/log_reader_input.h"
#include "mpcal/calibration_file.h"
#include "mpcal/error.h"
#include "mpcal/log_reader.h"
#include "test_util.h"

namespace mpcal {
namespace {

using ::testing::HasSubstr;
using testing::ReadFile;
using testing::ScratchDir;
using testing::TestDataPath;

std::vector<std::filesystem::path> Corpus(const std::string& target) {
  std::vector<std::filesystem::path> files;
  for (const auto& e :
       std::filesystem::directory_iterator(TestDataPath("../fuzz/" + target))) {
    if (e.is_regular_file()) files.push_back(e.path());
  }
  std::sort(files.begin(), files.end());
  return files;
}

// ----- calibration file -----

// Found by calibration_file_fuzzer: "iterations": 3495940595 was read as a
// long long and cast to int, wrapping to -799026701; writing the calibration
// back then failed its own check (iterations >= 0).
TEST(CalibrationFileFuzzRegression, IterationsBeyondAnIntAreRejectedNotWrapped) {
  const std::string text =
      ReadFile(TestDataPath("../fuzz/calibration_file/crash_iterations_overflow.json"));
  ASSERT_FALSE(text.empty());
  try {
    CalibrationFromJson(text, "crash.json");
    FAIL() << "accepted an iteration count beyond an int";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("'fit.iterations' must be at most 2147483647"));
  }
}

TEST(CalibrationFileFuzzRegression, IntegerFieldsOutOfRangeAreRejectedWithTheirName) {
  const nlohmann::json valid =
      nlohmann::json::parse(ReadFile(TestDataPath("bad/valid_calib.json")));
  ASSERT_NO_THROW(CalibrationFromJson(valid.dump(), "valid.json"));
  nlohmann::json fit = {{"positions", 13},
                        {"residual_rms_before_mps2", 0.5},
                        {"residual_rms_after_mps2", 0.001},
                        {"iterations", 5},
                        {"converged", true}};
  {
    nlohmann::json j = valid;
    j["fit"] = fit;
    EXPECT_EQ(CalibrationFromJson(j.dump(), "ok.json").fit->iterations, 5);
  }
  // Unsigned beyond long long (would wrap to -1), just beyond an int, negative.
  for (const auto& [key, value] :
       {std::pair<std::string, nlohmann::json>{"positions",
                                               std::numeric_limits<std::uint64_t>::max()},
        {"iterations", std::int64_t{std::numeric_limits<int>::max()} + 1},
        {"excluded_positions", -1}}) {
    nlohmann::json j = valid;
    j["fit"] = fit;
    j["fit"][key] = value;
    try {
      CalibrationFromJson(j.dump(), "bad.json");
      ADD_FAILURE() << key << " = " << value.dump() << " accepted";
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr("'fit." + key + "' must be at"));
    }
  }
}

// An IMU file's gyroscope block out of the plausible ranges (plausible.h):
// each is refused with the field's name instead of applied (an M of 1e308
// corrected rates to 1e305 rad/s). The corpus holds the same cases
// (tests/fuzz/calibration_file/gyro_*.json).
TEST(CalibrationFileFuzzRegression, GyroscopeBlockOutsidePlausibleRangesIsRefused) {
  const nlohmann::json valid =
      nlohmann::json::parse(ReadFile(TestDataPath("imu_trial_1.json")));
  ASSERT_TRUE(CalibrationFromJson(valid.dump(), "valid.json").gyroscope);
  const nlohmann::json counts =
      nlohmann::json::parse(ReadFile(TestDataPath("xsens_imu_half1.json")));
  ASSERT_TRUE(CalibrationFromJson(counts.dump(), "counts.json").gyroscope);
  struct Case {
    const nlohmann::json* base;
    nlohmann::json::json_pointer at;
    nlohmann::json value;
    std::string message;
  };
  using P = nlohmann::json::json_pointer;
  const std::vector<Case> cases = {
      {&valid, P("/gyroscope/m/0"), 1e308, "'gyroscope.m[0]' = 1e+308 is not a scale"},
      {&valid, P("/gyroscope/m/4"), -1000.0, "'gyroscope.m[4]' = -1000 is not a scale"},
      {&valid, P("/gyroscope/m/1"), 0.9, "'gyroscope.m[1]' = 0.9 is not a small angle"},
      {&valid,
       P("/gyroscope/bias_radps/2"),
       1e9,
       "'gyroscope.bias_radps[2]' = 1000000000"},
      {&valid,
       P("/gyroscope/bias_change_radps/0"),
       -1.0,
       "'gyroscope.bias_change_radps[0]'"},
      {&valid, P("/gyroscope/std/bias_radps/1"), -1e-3, "'gyroscope.std.bias_radps[1]'"},
      {&valid, P("/gyroscope/std/m/0"), 7.0, "'gyroscope.std.m[0]' = 7 is not a 1σ of M"},
      {&valid, P("/gyroscope/m_covariance/0"), -1.0, "'gyroscope.m_covariance[0]'"},
      {&valid, P("/gyroscope/m_covariance/1"), 1.0, "'gyroscope.m_covariance[1]'"},
      {&valid,
       P("/gyroscope/g_sensitivity_radps_per_mps2"),
       nlohmann::json(std::vector<double>(9, 0.5)),
       "'gyroscope.g_sensitivity_radps_per_mps2[0]' = 0.5 is beyond"},
      {&valid, P("/gyroscope/position_bias/3/bias_radps/0"), -500.0, "position_bias[3]"},
      {&valid,
       P("/gyroscope/position_bias/3/t_s"),
       1e20,
       "'gyroscope.position_bias[3].t_s'"},
      {&valid,
       P("/gyroscope/input/radps_per_unit"),
       2.0,
       "but units 'rads' mean 1 rad/s"},
      {&valid, P("/gyroscope/input/units"), "dps", "but units 'dps' mean 0.0174"},
      {&counts, P("/gyroscope/input/radps_per_unit"), 1e9, "is not a gyroscope's scale"},
      {&valid, P("/gyroscope/fit/residual_rms_after_rad"), -1.0, "not an angle"},
      {&valid, P("/gyroscope/fit/noise_std_radps"), 1e300, "not a gyroscope's noise"},
      {&valid, P("/gyroscope/fit/sample_period_s"), -0.01, "not a sample period"},
      {&valid,
       P("/gyroscope/fit/variance_factor"),
       -2.0,
       "'gyroscope.fit.variance_factor'"},
      {&valid,
       P("/gyroscope/fit/converged"),
       false,
       "'gyroscope.fit.converged' is false"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.at.to_string());
    nlohmann::json j = *c.base;
    j[c.at] = c.value;
    try {
      CalibrationFromJson(j.dump(), "bad.json");
      FAIL() << "accepted " << c.value.dump();
    } catch (const Error& e) {
      EXPECT_THAT(e.what(), HasSubstr(c.message));
    }
  }
  // Beyond a double, or not finite: not JSON numbers, refused by the parser.
  std::string text = valid.dump();
  const std::string m = "\"m\":[";
  text.insert(text.find(m) + m.size(), "1e400,");
  EXPECT_THROW(CalibrationFromJson(text, "inf.json"), Error);
}

TEST(CalibrationFileFuzzRegression, EveryCorpusInputReadsOrIsRejectedCleanly) {
  const auto files = Corpus("calibration_file");
  ASSERT_GE(files.size(), 5u);
  int read = 0;
  for (const auto& path : files) {
    SCOPED_TRACE(path.filename().string());
    const std::string text = ReadFile(path.string());
    try {
      const Calibration c = CalibrationFromJson(text, path.string());
      // What was read writes back and reads the same.
      const Calibration again = CalibrationFromJson(CalibrationToJson(c), "round-trip");
      EXPECT_EQ(ToVector(again.model), ToVector(c.model));
      // The seeds gyro_*.json hold a gyroscope block out of its ranges.
      EXPECT_FALSE(path.filename().string().starts_with("gyro_")) << "accepted";
      ++read;
    } catch (const Error&) {
      // rejected cleanly
    }
  }
  // The seeds include valid files (a calibration, a truth, the paper's).
  EXPECT_GE(read, 3);
}

// ----- log reader -----

TEST(LogReaderFuzzRegression, EveryCorpusInputReadsOrIsRejectedCleanly) {
  const auto files = Corpus("log_reader");
  ASSERT_GE(files.size(), 10u);
  const ScratchDir dir;
  int read = 0;
  for (const auto& path : files) {
    SCOPED_TRACE(path.filename().string());
    const std::string bytes = ReadFile(path.string());
    const auto in = fuzz::DecodeLogReaderInput(
        reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    const std::string log = dir.Write("log", std::string(in.log));
    try {
      if (in.use_scanner) {
        LogScanner scanner(log, in.options, in.scanner_parses_gyro);
        LogLine line;
        while (scanner.Next(&line)) {
          if (line.is_data) {
            EXPECT_TRUE(line.accel.allFinite());
          }
        }
      } else {
        const Recording rec = ReadLog(log, in.options);
        ASSERT_FALSE(rec.empty());
        for (std::size_t i = 1; i < rec.size(); ++i) {
          EXPECT_GT(rec.time_s[i], rec.time_s[i - 1]);
        }
        for (const auto& a : rec.accel) EXPECT_TRUE(a.allFinite());
      }
      ++read;
    } catch (const Error&) {
      // rejected cleanly
    }
  }
  EXPECT_GE(read, 10);
}

}  // namespace
}  // namespace mpcal
