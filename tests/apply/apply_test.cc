#include "mpcal/apply.h"

#include <charconv>
#include <cmath>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "mpcal/calibration_file.h"
#include "mpcal/error.h"
#include "mpcal/log_reader.h"
#include "mpcal/log_writer.h"
#include "mpcal/simulate.h"
#include "test_util.h"

namespace mpcal {
namespace {

using mpcal::testing::ReadFile;
using mpcal::testing::ScratchDir;
using ::testing::AllOf;
using ::testing::HasSubstr;

constexpr double kGravity = 9.80665;
// Per-axis white noise of the synthetic log (m/s²), and how many sigmas a
// check allows: |a| of one row is off by about the noise along gravity.
constexpr double kNoiseMps2 = 0.005;
constexpr double kSigmas = 5.0;
// Folding the model into one matrix changes only rounding.
constexpr double kFoldedRelative = 1e-13;

// A consumer-grade sensor (docs/method.md §6 magnitudes).
Calibration ConsumerCalibration(AccelUnits units, double mps2_per_unit) {
  Calibration c;
  c.gravity_mps2 = kGravity;
  c.input_units = units;
  c.mps2_per_unit = mps2_per_unit;
  c.model.bias_mps2 = {0.25, -0.18, 0.31};
  c.model.scale_factor_error = {0.021, -0.034, 0.012};
  c.model.theta_yz_rad = 0.004;
  c.model.theta_zx_rad = -0.007;
  c.model.theta_zy_rad = 0.011;
  return c;
}

std::vector<Eigen::Vector3d> Directions() {
  std::vector<Eigen::Vector3d> d = {{1, 0, 0},
                                    {-1, 0, 0},
                                    {0, 1, 0},
                                    {0, -1, 0},
                                    {0, 0, 1},
                                    {0, 0, -1},
                                    {1, 1, 0},
                                    {0, 1, -1},
                                    {1, -1, 1},
                                    {-1, 1, 1}};
  for (auto& v : d) v.normalize();
  return d;
}

struct SyntheticLog {
  std::string text;
  std::vector<std::pair<int, int>> still_rows;  // [first, last) data rows
  int rows = 0;
};

// A log as a logger with extra columns writes it: comments, a header,
// a temperature column between time and the axes, a status column at the end,
// `rows_per_position` still rows per direction with turns between them.
SyntheticLog MakeLog(const Calibration& truth,
                     double out_per_mps2,
                     int rows_per_position,
                     const std::string& eol = "\n") {
  std::mt19937_64 rng(42);
  std::normal_distribution<double> noise(0.0, kNoiseMps2);
  SyntheticLog log;
  log.text = "# logger 1.2, sensor 7" + eol + "% rate 100 Hz" + eol +
             "time,temp_C,acc_x,acc_y,acc_z,status" + eol;
  int row = 0;
  const auto dirs = Directions();
  for (std::size_t p = 0; p < dirs.size(); ++p) {
    const int first = row;
    for (int k = 0; k < rows_per_position; ++k, ++row) {
      Eigen::Vector3d y = truth.model.Forward(kGravity * dirs[p]);
      for (int i = 0; i < 3; ++i) y[i] += noise(rng);
      y *= out_per_mps2;
      log.text += fmt::format("{:.2f},{:.1f},{:.9g},{:.9g},{:.9g},OK{}",
                              row * 0.01,
                              21.0 + 0.1 * (row % 7),
                              y.x(),
                              y.y(),
                              y.z(),
                              eol);
    }
    log.still_rows.push_back({first, row});
    if (p + 1 < dirs.size()) {
      log.text += "# turn" + eol;
      // A hand turn: large accelerations, not at rest.
      for (int k = 0; k < 20; ++k, ++row) {
        log.text += fmt::format("{:.2f},21.0,{:.9g},{:.9g},{:.9g},MOVING{}",
                                row * 0.01,
                                out_per_mps2 * 3.0 * std::sin(k),
                                out_per_mps2 * 8.0,
                                out_per_mps2 * -5.0 * std::cos(k),
                                eol);
      }
    }
  }
  log.rows = row;
  return log;
}

std::vector<std::string> Lines(const std::string& text) {
  std::vector<std::string> lines;
  std::stringstream ss(text);
  std::string line;
  while (std::getline(ss, line)) lines.push_back(line);
  return lines;
}

std::vector<std::string> Fields(const std::string& line, char delimiter) {
  std::vector<std::string> fields;
  std::stringstream ss(line);
  std::string field;
  while (std::getline(ss, field, delimiter)) fields.push_back(field);
  return fields;
}

std::string ApplyError(const Calibration& calibration,
                       const std::string& input,
                       const std::string& output,
                       const ApplyOptions& options) {
  try {
    ApplyCalibration(calibration, input, output, options);
  } catch (const Error& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error";
  return "";
}

TEST(Corrector, EqualsCalibrationCorrect) {
  for (AccelUnits units : {AccelUnits::kMps2, AccelUnits::kG, AccelUnits::kCounts}) {
    const double k =
        units == AccelUnits::kCounts ? 1.0 / 4096.0 : *FixedMps2PerUnit(units);
    const Calibration c = ConsumerCalibration(units, k);
    const Corrector mps2(c, units, AccelUnits::kMps2);
    const Corrector g(c, units, AccelUnits::kG);
    for (const Eigen::Vector3d& d : Directions()) {
      const Eigen::Vector3d reading = c.model.Forward(kGravity * d) / k;
      const Eigen::Vector3d expected = c.Correct(reading);
      EXPECT_LE((mps2(reading) - expected).norm(), kFoldedRelative * expected.norm());
      EXPECT_LE((g(reading) * kGravity - expected).norm(),
                kFoldedRelative * expected.norm());
      EXPECT_NEAR(expected.norm(), kGravity, 1e-12);
    }
  }
}

TEST(Corrector, GAndMps2CalibrationsServeEachOther) {
  // Both units are fixed multiples of m/s²: a calibration made in g applies
  // to a log in m/s² and back.
  const Calibration in_g = ConsumerCalibration(AccelUnits::kG, kGravity);
  const Corrector c(in_g, AccelUnits::kMps2, AccelUnits::kMps2);
  const Eigen::Vector3d reading_mps2 = in_g.model.Forward({0, 0, kGravity});
  EXPECT_NEAR(c(reading_mps2).z(), kGravity, 1e-12);
}

TEST(CheckCalibrationApplies, CountsOnlyWithCounts) {
  const Calibration counts = ConsumerCalibration(AccelUnits::kCounts, 1.0 / 4096);
  EXPECT_NO_THROW(CheckCalibrationApplies(counts, AccelUnits::kCounts));
  try {
    CheckCalibrationApplies(counts, AccelUnits::kG);
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), AllOf(HasSubstr("raw counts"), HasSubstr("'g'")));
    // The advice: read the log in counts (the command says "--units counts").
    EXPECT_EQ(e.kind(), ErrorKind::kUnits);
    ASSERT_EQ(e.advice().settings.size(), 1u);
    EXPECT_EQ(e.advice().settings[0].option, Option::kLogUnits);
    EXPECT_EQ(e.advice().settings[0].value, "counts");
  }
  const Calibration mps2 = ConsumerCalibration(AccelUnits::kMps2, 1.0);
  EXPECT_THROW(CheckCalibrationApplies(mps2, AccelUnits::kCounts), Error);
  EXPECT_NO_THROW(CheckCalibrationApplies(mps2, AccelUnits::kG));
}

TEST(ApplyCalibration, StillRowsGetGravitysMagnitudeBack) {
  ScratchDir dir;
  const Calibration truth = ConsumerCalibration(AccelUnits::kMps2, 1.0);
  const SyntheticLog log = MakeLog(truth, 1.0, 100);
  const std::string in = dir.Write("in.csv", log.text);
  const ApplyResult result = ApplyCalibration(truth, in, dir.Path("out.csv"), {});
  EXPECT_EQ(result.data_rows, static_cast<std::size_t>(log.rows));
  EXPECT_EQ(result.other_lines, 3u + Directions().size() - 1);
  EXPECT_TRUE(result.warnings.empty()) << result.warnings.front();
  ASSERT_TRUE(result.rest_magnitude_mps2.has_value());
  EXPECT_NEAR(*result.rest_magnitude_mps2, kGravity, kSigmas * kNoiseMps2);

  const Recording raw = ReadLog(in, {});
  const Recording out = ReadLog(dir.Path("out.csv"), {});
  ASSERT_EQ(out.size(), raw.size());
  double raw_misses_sq = 0.0;
  for (auto [first, last] : log.still_rows) {
    Eigen::Vector3d mean_raw = Eigen::Vector3d::Zero();
    Eigen::Vector3d mean_out = Eigen::Vector3d::Zero();
    for (int i = first; i < last; ++i) {
      EXPECT_NEAR(out.accel[i].norm(), kGravity, kSigmas * kNoiseMps2) << "row " << i;
      mean_raw += raw.accel[i] / (last - first);
      mean_out += out.accel[i] / (last - first);
    }
    raw_misses_sq += std::pow(mean_raw.norm() - kGravity, 2) / log.still_rows.size();
    // The corrected means hit g to the noise of a mean.
    EXPECT_NEAR(
        mean_out.norm(), kGravity, kSigmas * kNoiseMps2 / std::sqrt(last - first));
  }
  // ... where the raw ones miss it by the sensor's errors (0.2 m/s² here).
  EXPECT_GT(std::sqrt(raw_misses_sq), 0.05);
}

TEST(ApplyCalibration, KeepsEverythingButTheAccelerometerNumbers) {
  ScratchDir dir;
  const Calibration truth = ConsumerCalibration(AccelUnits::kMps2, 1.0);
  for (const std::string eol : {"\n", "\r\n"}) {
    const SyntheticLog log = MakeLog(truth, 1.0, 5, eol);
    const std::string in = dir.Write("in.csv", log.text);
    ApplyCalibration(truth, in, dir.Path("out.csv"), {});
    const std::string out_text = ReadFile(dir.Path("out.csv"));
    // Same line ends, as many of them.
    const auto count = [&](const std::string& s) {
      std::size_t n = 0;
      for (std::size_t p = s.find(eol); p != std::string::npos;
           p = s.find(eol, p + eol.size()))
        ++n;
      return n;
    };
    EXPECT_EQ(count(out_text), count(log.text));
    const auto in_lines = Lines(log.text);
    const auto out_lines = Lines(out_text);
    ASSERT_EQ(in_lines.size(), out_lines.size());
    for (std::size_t i = 0; i < in_lines.size(); ++i) {
      if (in_lines[i].front() == '#' || in_lines[i].front() == '%' || i == 2) {
        EXPECT_EQ(out_lines[i], in_lines[i]);
        continue;
      }
      const auto a = Fields(in_lines[i], ',');
      const auto b = Fields(out_lines[i], ',');
      ASSERT_EQ(a.size(), 6u);
      ASSERT_EQ(b.size(), 6u);
      EXPECT_EQ(b[0], a[0]);  // time
      EXPECT_EQ(b[1], a[1]);  // temperature
      EXPECT_EQ(b[5], a[5]);  // status (and the \r of CRLF)
      EXPECT_NE(b[2], a[2]);
    }
  }
}

TEST(ApplyCalibration, WritesShortestRoundTripNumbers) {
  ScratchDir dir;
  const Calibration truth = ConsumerCalibration(AccelUnits::kMps2, 1.0);
  const std::string in = dir.Write("in.csv", "t,ax,ay,az\n0.5,0.3,-0.2,9.9\n");
  ApplyCalibration(truth, in, dir.Path("out.csv"), {});
  const auto fields = Fields(Lines(ReadFile(dir.Path("out.csv")))[1], ',');
  const Eigen::Vector3d expected = Corrector(
      truth, AccelUnits::kMps2, AccelUnits::kMps2)(Eigen::Vector3d(0.3, -0.2, 9.9));
  for (int i = 0; i < 3; ++i) {
    char shortest[32];
    const auto r = std::to_chars(shortest, shortest + 32, expected[i]);
    EXPECT_EQ(fields[1 + i], std::string(shortest, r.ptr));
  }
}

TEST(ApplyCalibration, OutputUnitsAndDecimalCommas) {
  ScratchDir dir;
  const Calibration truth = ConsumerCalibration(AccelUnits::kMps2, 1.0);
  const Eigen::Vector3d y = truth.model.Forward({0, 0, kGravity});
  const std::string in = dir.Write(
      "in.csv", fmt::format("zeit;ax;ay;az\n1,5;{};{};{}\n", y.x(), y.y(), y.z()));
  // The sniffer sees decimal commas only where the data has no dots.
  std::string text = ReadFile(in);
  for (std::size_t i = text.find('\n'); i < text.size(); ++i) {
    if (text[i] == '.') text[i] = ',';
  }
  dir.Write("in.csv", text);
  ApplyOptions options;
  options.log.columns = "t=zeit";
  options.out_units = AccelUnits::kG;
  ApplyCalibration(truth, in, dir.Path("out.csv"), options);
  const auto fields = Fields(Lines(ReadFile(dir.Path("out.csv")))[1], ';');
  ASSERT_EQ(fields.size(), 4u);
  EXPECT_EQ(fields[0], "1,5");
  std::string z = fields[3];
  ASSERT_EQ(z.find('.'), std::string::npos);
  std::replace(z.begin(), z.end(), ',', '.');
  EXPECT_NEAR(std::stod(z), 1.0, 1e-12);
}

TEST(ApplyCalibration, WarnsWhenTheMagnitudeAtRestIsNotGravity) {
  ScratchDir dir;
  const Calibration truth = ConsumerCalibration(AccelUnits::kMps2, 1.0);
  // The log is in g but is read as m/s² (the calibration's units).
  const SyntheticLog log = MakeLog(truth, 1.0 / kGravity, 100);
  const std::string in = dir.Write("in.csv", log.text);
  const ApplyResult result = ApplyCalibration(truth, in, dir.Path("out.csv"), {});
  EXPECT_TRUE(result.warnings.empty());
  ASSERT_TRUE(result.rest_mismatch);
  EXPECT_THAT(result.rest_mismatch->what, HasSubstr("magnitude at rest"));
  // The advice: read the log in g (the command says "--units g").
  EXPECT_EQ(result.rest_mismatch->kind, RestMismatchKind::kLooksLikeG);
  ASSERT_EQ(result.rest_mismatch->advice.settings.size(), 1u);
  EXPECT_EQ(result.rest_mismatch->advice.settings[0].option, Option::kLogUnits);
  EXPECT_EQ(result.rest_mismatch->advice.settings[0].value, "g");
  // Read with the right units the same log is fine.
  ApplyOptions in_g;
  in_g.log.units = AccelUnits::kG;
  const ApplyResult right = ApplyCalibration(truth, in, dir.Path("out.csv"), in_g);
  EXPECT_TRUE(right.warnings.empty());
  EXPECT_FALSE(right.rest_mismatch);
}

TEST(ApplyCalibration, RefusesMismatchedUnitsBeforeWritingAnything) {
  ScratchDir dir;
  const Calibration counts = ConsumerCalibration(AccelUnits::kCounts, 1.0 / 4096);
  const std::string in = dir.Write("in.csv", "t,ax,ay,az\n0,0,0,1\n");
  ApplyOptions options;
  options.log.units = AccelUnits::kG;
  EXPECT_THAT(ApplyError(counts, in, dir.Path("out.csv"), options),
              HasSubstr("raw counts"));
  EXPECT_FALSE(std::filesystem::exists(dir.Path("out.csv")));
}

TEST(ApplyCalibration, RefusesToOverwriteItsInput) {
  ScratchDir dir;
  const std::string in = dir.Write("in.csv", "t,ax,ay,az\n0,0,0,9.8\n");
  EXPECT_THAT(ApplyError(ConsumerCalibration(AccelUnits::kMps2, 1.0), in, in, {}),
              HasSubstr("does not overwrite its input"));
  EXPECT_EQ(ReadFile(in), "t,ax,ay,az\n0,0,0,9.8\n");
}

TEST(ApplyCalibration, MalformedLineLeavesNoOutput) {
  ScratchDir dir;
  const std::string in =
      dir.Write("in.csv", "t,ax,ay,az\n0,0,0,9.8\n0.1,0,x,9.8\n0.2,0,0,9.8\n");
  EXPECT_THAT(
      ApplyError(
          ConsumerCalibration(AccelUnits::kMps2, 1.0), in, dir.Path("out.csv"), {}),
      AllOf(HasSubstr("in.csv:3"), HasSubstr("'x'")));
  EXPECT_FALSE(std::filesystem::exists(dir.Path("out.csv")));
}

TEST(ApplyCalibration, TruncatedLastLineDroppedWithWarning) {
  ScratchDir dir;
  const std::string in =
      dir.Write("in.csv", "t,ax,ay,az\n0,0,0,9.8\n0.1,0,0,9.8\n0.2,0,");
  const ApplyResult r = ApplyCalibration(
      ConsumerCalibration(AccelUnits::kMps2, 1.0), in, dir.Path("out.csv"), {});
  EXPECT_EQ(r.data_rows, 2u);
  EXPECT_EQ(Lines(ReadFile(dir.Path("out.csv"))).size(), 3u);
  EXPECT_THAT(r.warnings.front(), HasSubstr("incomplete"));
}

TEST(ApplyOptions, DefaultsAreValidAndBadFieldsNamed) {
  EXPECT_EQ(ApplyOptions{}.Validate(), "");
  ApplyOptions counts;
  counts.out_units = AccelUnits::kCounts;
  EXPECT_THAT(counts.Validate(), HasSubstr("out_units"));
  ApplyOptions tolerance;
  tolerance.rest_tolerance = 0.0;
  EXPECT_THAT(tolerance.Validate(), HasSubstr("rest_tolerance"));
  ApplyOptions rate;
  rate.log.rate_hz = -5;
  EXPECT_THAT(rate.Validate(), HasSubstr("log.rate_hz"));
}

TEST(ApplyCalibration, TruthOfASimulatedSessionGivesGravityAtEveryPosition) {
  ScratchDir dir;
  SimulateStaticOptions options;
  options.device = FindPreset("mti-g");
  options.seed = 7;
  options.dwell_s = 4.0;
  const SimulatedSession session = SimulateStatic(options, kGravity);
  LogWriteOptions exact;
  exact.significant_digits = 0;
  WriteRecordingFile(dir.Path("session.csv"), session.recording, exact);
  WriteCalibrationFile(dir.Path("truth.json"), session.truth);

  ApplyOptions apply;
  apply.log.units = session.recording.units;
  const ApplyResult result = ApplyCalibration(ReadCalibrationFile(dir.Path("truth.json")),
                                              dir.Path("session.csv"),
                                              dir.Path("corrected.csv"),
                                              apply);
  EXPECT_TRUE(result.warnings.empty()) << result.warnings.front();
  const Recording out = ReadLog(dir.Path("corrected.csv"), {});
  ASSERT_EQ(out.size(), session.recording.size());
  // Per-sample noise (m/s²) as the simulator defines it: σ = ND·√(rate/2).
  const double sigma = options.device.noise_density_mps2_per_sqrt_hz *
                       std::sqrt(options.device.rate_hz / 2.0);
  ASSERT_EQ(session.still_ranges.size(), 26u);
  for (auto [begin, end] : session.still_ranges) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (std::size_t i = begin; i < end; ++i) mean += out.accel[i];
    mean /= static_cast<double>(end - begin);
    // Quantisation of the preset adds at most resolution/√12 per axis.
    const double noise =
        std::hypot(sigma, options.device.resolution_mps2 / std::sqrt(12.0));
    EXPECT_NEAR(mean.norm(), kGravity, kSigmas * noise / std::sqrt(end - begin))
        << "position at sample " << begin;
  }
}

}  // namespace
}  // namespace mpcal
