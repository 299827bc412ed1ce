// Imports of the tools' files: the calibration they give corrects a raw
// reading as the tool's own formula does (written here from its source),
// an import exported again gives the same numbers, and bad or foreign files
// are refused with the file and the key named.
#include <cmath>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "mpcal/calibration_file.h"
#include "mpcal/error.h"
#include "mpcal/export.h"
#include "mpcal/noise_file.h"
#include "test_util.h"

namespace mpcal {
namespace {

// imu_tk's CalibratedTriad_::save of an accelerometer (Eigen's stream
// output, 6 significant digits): T upper unit-triangular, K, B in counts.
const char* kImuTkAccel =
    "        1 -0.00161123  0.00402457\n"
    "        0          1 -0.00300751\n"
    "       -0          0          1\n"
    "\n"
    "0.00241793          0          0\n"
    "         0 0.00243001          0\n"
    "         0          0 0.00240467\n"
    "\n"
    "32716.1\n"
    "32865.8\n"
    "32773.2\n"
    "\n";
const char* kImuTkGyro =
    "           1   0.00927479   -0.0117672\n"
    "  -0.0114379            1   0.00398781\n"
    "   0.0134621  -0.00361722            1\n"
    "\n"
    "0.000209286           0           0\n"
    "          0 0.000209897           0\n"
    "          0           0 0.000209483\n"
    "\n"
    "32765.2\n"
    "32806.8\n"
    "32753.1\n"
    "\n";

struct Triad {
  Eigen::Matrix3d t, k;
  Eigen::Vector3d b;
};

// imu_tk's load(): 21 numbers with >>.
Triad LoadLikeImuTk(const std::string& text) {
  std::istringstream in(text);
  Triad t;
  for (int i = 0; i < 9; ++i) in >> t.t(i / 3, i % 3);
  for (int i = 0; i < 9; ++i) in >> t.k(i / 3, i % 3);
  for (int i = 0; i < 3; ++i) in >> t.b[i];
  EXPECT_FALSE(in.fail());
  return t;
}

ImportOptions Counts() {
  ImportOptions o;
  o.accel_units = AccelUnits::kCounts;
  o.gyro_units = GyroUnits::kCounts;
  o.gravity_mps2 = 9.81744;
  return o;
}

const ExportFormat& Format(const char* name) {
  const ExportFormat* f = FindExportFormat(name);
  EXPECT_NE(f, nullptr) << name;
  return *f;
}

TEST(ImportImuTk, CorrectsAsImuTkDoesUpToItsFrame) {
  const ImportedCalibration imported =
      Import(Format("imu-tk"),
             {ImportFile{"acc.calib", kImuTkAccel}, ImportFile{"gyro.calib", kImuTkGyro}},
             Counts());
  const Calibration& c = imported.calibration;
  ASSERT_TRUE(c.gyroscope);
  EXPECT_FALSE(c.std);
  EXPECT_EQ(c.imported_from, std::optional<std::string>("imu_tk .calib"));
  const Triad a = LoadLikeImuTk(kImuTkAccel);
  const Triad g = LoadLikeImuTk(kImuTkGyro);
  // The frames differ by one rotation R: found from three readings, it must
  // then hold for every other one.
  std::vector<Eigen::Vector3d> raws = {{36771, 32865, 32773},
                                       {32716, 28810, 32773},
                                       {32716, 32865, 36829},
                                       {35000, 30000, 34000},
                                       {30000, 34500, 31000}};
  Eigen::Matrix3d tk, mp;
  for (int i = 0; i < 3; ++i) {
    tk.col(i) = a.t * a.k * (raws[static_cast<std::size_t>(i)] - a.b);
    mp.col(i) = c.Correct(raws[static_cast<std::size_t>(i)]);
  }
  const Eigen::Matrix3d r = tk * mp.inverse();  // tk = R·mp
  EXPECT_LT((r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(),
            1e-9);
  EXPECT_NEAR(r.determinant(), 1.0, 1e-9);
  for (const Eigen::Vector3d& raw : raws) {
    const Eigen::Vector3d want = a.t * a.k * (raw - a.b);
    EXPECT_LT((r * c.Correct(raw) - want).norm(), 1e-9 * want.norm());
    // The gyroscope in the same frame as imu_tk's accelerometer.
    const Eigen::Vector3d w_raw = raw * 0.1 + Eigen::Vector3d(29000, 29500, 29400);
    const Eigen::Vector3d w_want = g.t * g.k * (w_raw - g.b);
    EXPECT_LT((r * c.gyroscope->Correct(w_raw) - w_want).norm(), 1e-9 * w_want.norm());
  }
}

TEST(ImportImuTk, ExportedAgainGivesTheSameNumbers) {
  const ImportedCalibration imported =
      Import(Format("imu-tk"),
             {ImportFile{"acc.calib", kImuTkAccel}, ImportFile{"gyro.calib", kImuTkGyro}},
             Counts());
  ExportSources s;
  s.calibration = &imported.calibration;
  s.calibration_path = "imported.json";
  for (const auto& [format, original] :
       {std::pair{"imu-tk-accel", kImuTkAccel}, std::pair{"imu-tk-gyro", kImuTkGyro}}) {
    const ExportedFile out = Export(Format(format), s, ExportOptions{});
    const Triad want = LoadLikeImuTk(original);
    const Triad got = LoadLikeImuTk(out.text);
    EXPECT_LT((got.t - want.t).cwiseAbs().maxCoeff(), 1e-12) << format;
    EXPECT_LT(((got.k - want.k).cwiseQuotient(want.k + Eigen::Matrix3d::Identity()))
                  .cwiseAbs()
                  .maxCoeff(),
              1e-12)
        << format;
    EXPECT_LT((got.b - want.b).cwiseAbs().maxCoeff(), 1e-9) << format;
  }
}

TEST(ImportImuTk, TheFileThroughTheCalibrationFileKeepsItsState) {
  const ImportedCalibration imported =
      Import(Format("imu-tk"), {ImportFile{"acc.calib", kImuTkAccel}}, Counts());
  const Calibration back =
      CalibrationFromJson(CalibrationToJson(imported.calibration), "imported.json");
  EXPECT_EQ(back.imported_from, std::optional<std::string>("imu_tk .calib"));
  EXPECT_FALSE(back.std);
  EXPECT_FALSE(back.gyroscope);
  // A file that says it was imported but carries a 1σ is not one mpcal wrote.
  std::string text = CalibrationToJson(imported.calibration);
  const auto at = text.find("\"imported_from\"");
  ASSERT_NE(at, std::string::npos);
  text.insert(at,
              "\"std\": {\"bias_mps2\": [0.1, 0.1, 0.1], \"scale_factor_error\": [0.001, "
              "0.001, 0.001], \"non_orthogonality_rad\": {\"yz\": 0.001, \"zx\": 0.001, "
              "\"zy\": 0.001}},\n");
  EXPECT_THROW(CalibrationFromJson(text, "x.json"), Error);
}

void ExpectRefused(const char* format,
                   const std::vector<ImportFile>& files,
                   const std::string& words) {
  try {
    Import(Format(format), files, Counts());
    ADD_FAILURE() << "accepted: " << words;
  } catch (const Error& e) {
    EXPECT_THAT(std::string(e.what()), ::testing::HasSubstr(words)) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
  }
}

TEST(ImportImuTk, BadFilesAreRefusedNamingTheFile) {
  ExpectRefused("imu-tk",
                {ImportFile{"a.calib", "1 0 0 0 1 0 0 0 1\n1 0 0 0 1 0 0 0 1\n0 0"}},
                "'a.calib' holds 20 numbers");
  ExpectRefused("imu-tk",
                {ImportFile{"a.calib", "1 0 0 0 1 0 0 x 1"}},
                "'x' is not a finite number");
  ExpectRefused(
      "imu-tk",
      {ImportFile{"a.calib", "1 0 0 0 1 0 0 0 1\n1 0.5 0 0 1 0 0 0 1\n0 0 0\n"}},
      "off its diagonal");
  ExpectRefused("imu-tk",
                {ImportFile{"a.calib", "1 0 0 0 1 0 0 0 1\n1 0 0 0 1 0 0 0 0\n0 0 0\n"}},
                "singular");
  ExpectRefused(
      "imu-tk",
      {ImportFile{"a.calib", "1 0 0 0 1 0 0 0 1\n1 0 0 0 1 0 0 0 1\n0 0 0\n7\n"}},
      "text after the 21 numbers");
  ExpectRefused("imu-tk", {}, "takes 1 to 2 files");
}

const char* kKalibrCamChain =
    "cam0:\n  camera_model: pinhole\n  intrinsics: [458.6, 457.3, 367.2, 248.4]\n";

std::string KalibrImu(const std::string& model, const std::string& c_gyro_i) {
  return "imu0:\n  model: " + model +
         "\n  accelerometers:\n    M:\n    - [1.002, 0.0, 0.0]\n    - [0.001, 0.998, "
         "0.0]\n    - [-0.002, 0.003, 1.001]\n  gyroscopes:\n    M:\n    - [0.999, 0.0, "
         "0.0]\n    - [0.002, 1.003, 0.0]\n    - [0.001, -0.001, 0.997]\n    A:\n    - "
         "[0.0001, 0.0, 0.0]\n    - [0.0, 0.0002, 0.0]\n    - [0.0, 0.0, -0.0001]\n    "
         "C_gyro_i:\n" +
         c_gyro_i;
}
const char* kRotation =
    "    - [0.9999995, -0.0009999998, 0.0]\n    - [0.0009999998, 0.9999995, 0.0]\n    - "
    "[0.0, 0.0, 1.0]\n";

TEST(ImportKalibr, CorrectsAsKalibrsModelSays) {
  const ImportedCalibration imported =
      Import(Format("kalibr-scale-misalignment"),
             {ImportFile{"imu.yaml", KalibrImu("scale-misalignment", kRotation)}},
             ImportOptions{});
  const Calibration& c = imported.calibration;
  ASSERT_TRUE(c.gyroscope);
  Eigen::Matrix3d ma, mg, a, cg;
  ma << 1.002, 0, 0, 0.001, 0.998, 0, -0.002, 0.003, 1.001;
  mg << 0.999, 0, 0, 0.002, 1.003, 0, 0.001, -0.001, 0.997;
  a << 0.0001, 0, 0, 0, 0.0002, 0, 0, 0, -0.0001;
  cg << 0.9999995, -0.0009999998, 0, 0.0009999998, 0.9999995, 0, 0, 0, 1;
  // Kalibr's forward model (no biases in its file): α = M_a·a,
  // ω_m = M_g·C·ω + A·C·a. mpcal's correction must invert it.
  const Eigen::Vector3d f(0.3, -9.7, 1.2), w(0.5, -0.2, 1.1);
  const Eigen::Vector3d alpha = ma * f;
  const Eigen::Vector3d w_m = mg * cg * w + a * cg * f;
  EXPECT_LT((c.Correct(alpha) - f).norm(), 1e-12);
  EXPECT_LT((c.gyroscope->Correct(w_m, f) - w).norm(), 1e-12);
}

TEST(ImportKalibr, ForeignAndBrokenFilesAreRefused) {
  const char* k = "kalibr-scale-misalignment";
  ExpectRefused(k, {ImportFile{"chain.yaml", kKalibrCamChain}}, "a camera chain");
  ExpectRefused(k,
                {ImportFile{"imu.yaml", KalibrImu("calibrated", kRotation)}},
                "imu0.model is 'calibrated'");
  ExpectRefused(k,
                {ImportFile{"imu.yaml",
                            KalibrImu("scale-misalignment",
                                      "    - [1, 0.1, 0]\n    - [0, 1, 0]\n    "
                                      "- [0, 0, 1]\n")}},
                "gyroscopes.C_gyro_i: not a rotation");
  std::string missing = KalibrImu("scale-misalignment", kRotation);
  missing.replace(missing.find("    A:"), 2 + 4, "    B:");
  ExpectRefused(k, {ImportFile{"imu.yaml", missing}}, "'imu0.gyroscopes.A' is missing");
  ExpectRefused(k, {ImportFile{"imu.yaml", "imu0: [1, 2"}}, "not YAML");
  std::string upper = KalibrImu("scale-misalignment", kRotation);
  upper.replace(upper.find("[1.002, 0.0, 0.0]"), 17, "[1.002, 0.5, 0.0]");
  ExpectRefused(k, {ImportFile{"imu.yaml", upper}}, "must be lower triangular");
}

// Every number on the lines that are not comments.
std::vector<double> Numbers(const std::string& text) {
  std::vector<double> out;
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.starts_with("#") || line.starts_with("%")) continue;
    for (char& ch : line) {
      if (ch == '[' || ch == ']' || ch == ',' || ch == ':') ch = ' ';
    }
    std::istringstream words(line);
    std::string w;
    while (words >> w) {
      try {
        std::size_t used = 0;
        const double v = std::stod(w, &used);
        if (used == w.size()) out.push_back(v);
      } catch (const std::exception&) {
      }
    }
  }
  return out;
}

TEST(ExportKalibr, ImportOfTheExportGivesTheCalibrationAndTheFileBack) {
  const Calibration c =
      ReadCalibrationFile(std::string(MPCAL_TEST_DATA_DIR) + "/xsens_imu_half1.json");
  const NoiseFile noise =
      ReadNoiseFile(std::string(MPCAL_TEST_DATA_DIR) + "/noise_still.json");
  ExportSources s;
  s.calibration = &c;
  s.noise = &noise;
  s.calibration_path = "imu.json";
  s.noise_path = "noise.json";
  for (const char* format : {"kalibr-scale-misalignment", "openvins"}) {
    const ExportedFile out = Export(Format(format), s, ExportOptions{});
    const ImportedCalibration back =
        Import(Format(format), {ImportFile{"exported.yaml", out.text}}, ImportOptions{});
    // The file is for readings in m/s² and rad/s (the counts times the
    // nominal factors); the biases are not in it.
    const Calibration& b = back.calibration;
    EXPECT_LT(
        (b.Affine().linear - c.Affine().linear / c.mps2_per_unit).cwiseAbs().maxCoeff(),
        1e-12)
        << format;
    EXPECT_LT((b.gyroscope->m - c.gyroscope->m).cwiseAbs().maxCoeff(), 1e-12) << format;
    EXPECT_LT((*b.gyroscope->g_sensitivity_radps_per_mps2 -
               *c.gyroscope->g_sensitivity_radps_per_mps2)
                  .cwiseAbs()
                  .maxCoeff(),
              1e-15)
        << format;
    ExportSources again = s;
    again.calibration = &b;
    const std::vector<double> first = Numbers(out.text);
    const std::vector<double> second = Numbers(Export(Format(format), again, {}).text);
    ASSERT_EQ(first.size(), second.size()) << format;
    for (std::size_t i = 0; i < first.size(); ++i) {
      EXPECT_NEAR(first[i], second[i], 1e-12 * (1.0 + std::abs(first[i])))
          << format << " " << i;
    }
  }
}

TEST(ImportOpenVins, ForeignAndBrokenFilesAreRefused) {
  ExpectRefused(
      "openvins", {ImportFile{"chain.yaml", kKalibrCamChain}}, "a camera chain");
  ExpectRefused("openvins",
                {ImportFile{"imu.yaml",
                            "%YAML:1.0\nimu0:\n  model: kalibr\n  Tw:\n    - [1, 0, 0]\n "
                            "   - [0, 1, 0]\n    - [0, 0, 0]\n"}},
                "imu0.Tw: the matrix is singular");
  ExpectRefused("openvins",
                {ImportFile{"imu.yaml",
                            "%YAML:1.0\nimu0:\n  model: kalibr\n  Tw:\n    - [1, 0.1, "
                            "0]\n    - [0, 1, 0]\n    - [0, 0, 1]\n"}},
                "must be lower triangular");
  ExpectRefused("openvins",
                {ImportFile{"imu.yaml", "%YAML:1.0\nimu0:\n  rostopic: /imu0\n"}},
                "neither Tw nor Ta");
}

}  // namespace
}  // namespace mpcal
