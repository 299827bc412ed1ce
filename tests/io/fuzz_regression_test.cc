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
