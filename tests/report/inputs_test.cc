// Reading the report's inputs: verification results, trajectory CSVs, and
// the files behind a report, with errors that name the file and the field.
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mpcal/calibration_file.h"
#include "mpcal/error.h"
#include "mpcal/report.h"
#include "report_fixtures.h"
#include "test_util.h"

namespace mpcal {
namespace {

using ::testing::HasSubstr;

std::string ErrorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

constexpr const char* kResult = R"({
  "format": "mpcal.verification/1",
  "reference": {"path_length_m": 129.1, "start_end_distance_m": 0.21},
  "raw": {"start_end_distance_m": 15.3, "horizontal_rms_m": 6.1,
          "horizontal_max_m": 15.3, "path_length_m": 133.2},
  "corrected": {"start_end_distance_m": 1.6, "horizontal_rms_m": 0.7,
                "horizontal_max_m": 1.6, "path_length_m": 130.4},
  "integration": {"mount": "z-up", "stops": 4},
  "warnings": ["no stop detected after 60 s"],
  "trajectories": {"reference": "walk_reference.csv", "raw": "/abs/raw.csv"}
})";

TEST(VerificationJson, ReadsTheFiguresAndResolvesTrajectoryPaths) {
  const VerificationSummary v = ParseVerificationJson(kResult, "/data/run/result.json");
  EXPECT_DOUBLE_EQ(v.reference.start_end_distance_m, 0.21);
  EXPECT_DOUBLE_EQ(*v.reference.path_length_m, 129.1);
  EXPECT_DOUBLE_EQ(v.raw.start_end_distance_m, 15.3);
  EXPECT_DOUBLE_EQ(*v.raw.horizontal_rms_m, 6.1);
  ASSERT_TRUE(v.corrected);
  EXPECT_DOUBLE_EQ(v.corrected->start_end_distance_m, 1.6);
  ASSERT_EQ(v.trajectory_files.size(), 2u);
  EXPECT_EQ(v.trajectory_files[0].second, "/data/run/walk_reference.csv");
  EXPECT_EQ(v.trajectory_files[1].second, "/abs/raw.csv");
  EXPECT_EQ(v.warnings.size(), 1u);
  EXPECT_THAT(v.details,
              ::testing::Contains(
                  std::pair<std::string, std::string>("integration.mount", "z-up")));
}

TEST(VerificationJson, RejectsOtherFormatsAndMissingFieldsByName) {
  EXPECT_THAT(ErrorOf([] { ParseVerificationJson("{", "r.json"); }),
              HasSubstr("r.json: not valid JSON"));
  EXPECT_THAT(
      ErrorOf([] {
        ParseVerificationJson(R"({"format": "mpcal.accelerometer/1"})", "c.json");
      }),
      HasSubstr("c.json: format 'mpcal.accelerometer/1' is not 'mpcal.verification/1'"));
  // A file of another kind: the advice is the stage that writes the kind
  // expected (the command line spells it "written by 'mpcal verify'").
  try {
    ParseVerificationJson(R"({"format": "mpcal.accelerometer/1"})", "c.json");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kFormat);
    EXPECT_EQ(e.advice().stage, Stage::kVerify);
  }
  EXPECT_THAT(ErrorOf([] {
                ParseVerificationJson(R"({"format": "mpcal.verification/2"})", "r.json");
              }),
              HasSubstr("is version 2 of the format; this mpcal reads version 1"));
  EXPECT_THAT(
      ErrorOf([] { ParseVerificationJson("[1, 2]", "r.json"); }),
      HasSubstr(
          "r.json: expected a JSON object with \"format\": \"mpcal.verification/1\""));
  EXPECT_THAT(ErrorOf([] { ParseVerificationJson(R"({"raw": {}})", "r.json"); }),
              HasSubstr("r.json: no 'format' field (expected \"format\": "
                        "\"mpcal.verification/1\")"));
  EXPECT_THAT(
      ErrorOf([] {
        ParseVerificationJson(
            R"({"format": "mpcal.verification/1",
                        "reference": {"start_end_distance_m": 0.2},
                        "raw": {"start_end_distance_m": "far"}})",
            "r.json");
      }),
      HasSubstr("field 'raw.start_end_distance_m' must be a number, found a string"));
  EXPECT_THAT(ErrorOf([] {
                ParseVerificationJson(
                    R"({"format": "mpcal.verification/1", "reference": {}})", "r.json");
              }),
              HasSubstr("missing field 'reference.start_end_distance_m'"));
}

TEST(TrajectoryCsv, ReadsTheColumnsByName) {
  testing::ScratchDir dir;
  const std::string path = dir.Write(
      "p.csv", "t_s,e_m,n_m,u_m,q\n10.0,1.5,-2.0,0.1,1\r\n10.2,1.6,-2.1,0.1,1\n");
  const EastNorthPath p = ReadEastNorthCsv(path);
  ASSERT_EQ(p.time_s.size(), 2u);
  EXPECT_DOUBLE_EQ(p.time_s[1], 10.2);
  EXPECT_DOUBLE_EQ(p.east_m[0], 1.5);
  EXPECT_DOUBLE_EQ(p.north_m[1], -2.1);
}

TEST(TrajectoryCsv, ErrorsNameTheFileAndLine) {
  testing::ScratchDir dir;
  EXPECT_THAT(ErrorOf([&] { ReadEastNorthCsv(dir.Write("a.csv", "t,x,y\n1,2,3\n")); }),
              HasSubstr("a.csv:1: expected a header naming"));
  EXPECT_THAT(
      ErrorOf([&] { ReadEastNorthCsv(dir.Write("b.csv", "t,e,n\n1,2,3\n1,x,3\n")); }),
      HasSubstr("b.csv:3: column 2: \"x\" is not a finite number"));
  EXPECT_THAT(ErrorOf([&] { ReadEastNorthCsv(dir.Write("c.csv", "t,e,n\n1,2\n")); }),
              HasSubstr("c.csv:2: 2 columns, expected at least 3"));
  EXPECT_THAT(ErrorOf([&] { ReadEastNorthCsv(dir.Write("d.csv", "t,e,n\n")); }),
              HasSubstr("d.csv: no data rows"));
  EXPECT_THAT(ErrorOf([&] { ReadEastNorthCsv(dir.Path("none.csv")); }),
              HasSubstr("none.csv: cannot open"));
}

TEST(LoadReportInputs, ReadsTheFilesAndListsThem) {
  testing::ScratchDir dir;
  const Calibration c = testing::FixtureCalibration(testing::CubeDirections());
  const std::string calib = dir.Path("calib.json");
  WriteCalibrationFile(calib, c);
  const std::string result = dir.Write("result.json", kResult);
  dir.Write("walk_reference.csv", "t_s,e_m,n_m\n0,0,0\n1,1,0\n");
  dir.Write("t-raw.csv", "t_s,e_m,n_m\n0,0,0\n1,1.1,0\n");
  dir.Write("t-reference.csv", "t_s,e_m,n_m\n0,0,0\n1,1,0\n");
  ReportFiles files;
  files.calibration = calib;
  files.verification = result;
  // The result names /abs/raw.csv, which does not exist: a clear error.
  EXPECT_THAT(ErrorOf([&] { LoadReportInputs(files); }),
              HasSubstr("/abs/raw.csv: cannot open"));
  // A prefix overrides the names in the result; "corrected" is optional.
  files.verification_trajectories = dir.Path("t");
  const ReportInputs in = LoadReportInputs(files);
  ASSERT_TRUE(in.calibration);
  EXPECT_EQ(in.calibration->positions.size(), 26u);
  ASSERT_TRUE(in.verification);
  ASSERT_TRUE(in.verification->raw_path);
  EXPECT_DOUBLE_EQ(in.verification->raw_path->east_m[1], 1.1);
  EXPECT_FALSE(in.verification->corrected_path);
  EXPECT_EQ(in.input_files.size(), 4u);  // calibration, result, two trajectories
  EXPECT_EQ(in.input_files[0].second, calib);
}

TEST(LoadReportInputs, RefusesMissingAndWrongFiles) {
  testing::ScratchDir dir;
  ReportFiles files;
  EXPECT_THAT(ErrorOf([&] { LoadReportInputs(files); }), HasSubstr("no input"));
  files.calibration = dir.Path("missing.json");
  EXPECT_THAT(ErrorOf([&] { LoadReportInputs(files); }), HasSubstr("missing.json"));
  // A verification result given as the repeatability table.
  files.calibration.clear();
  files.repeatability = dir.Write("r.json", kResult);
  EXPECT_THAT(ErrorOf([&] { LoadReportInputs(files); }), HasSubstr("r.json"));
  files.repeatability.clear();
  files.verification = dir.path().string();
  EXPECT_THAT(ErrorOf([&] { LoadReportInputs(files); }), HasSubstr("is a directory"));
  files.verification.clear();
  files.verification_trajectories = "x_";
  files.calibration = "c.json";
  EXPECT_THAT(ErrorOf([&] { LoadReportInputs(files); }),
              HasSubstr("verification_trajectories needs verification"));
}

}  // namespace
}  // namespace mpcal
