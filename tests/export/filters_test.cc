// The filters' noise files and the autopilots' parameters, each checked with
// its tool's own formula written here from the tool's source (not through
// mpcal's model): the noise a filter propagates from the file's values
// against the still record's own scatter, and the autopilot's correction of
// raw readings against mpcal's.
#include <array>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include "export/filter_formats.h"
#include "mpcal/calibration_file.h"
#include "mpcal/error.h"
#include "mpcal/export.h"
#include "mpcal/noise_file.h"
#include "test_util.h"

namespace mpcal {
namespace {

using mpcal::testing::TestDataPath;
using ::testing::HasSubstr;

constexpr double kPi = 3.14159265358979323846;

// The still record of tests/data: t, ax, ay, az, gx, gy, gz (s, m/s², rad/s).
struct StillRecord {
  std::vector<std::array<double, 3>> acc, gyro;
  double rate_hz = 0.0;
};

StillRecord ReadStill() {
  std::ifstream in(TestDataPath("noise_still.csv"));
  std::string line;
  std::getline(in, line);
  StillRecord r;
  double t0 = 0.0, t = 0.0;
  while (std::getline(in, line)) {
    std::replace(line.begin(), line.end(), ',', ' ');
    std::istringstream s(line);
    std::array<double, 3> a{}, g{};
    s >> t >> a[0] >> a[1] >> a[2] >> g[0] >> g[1] >> g[2];
    if (r.acc.empty()) t0 = t;
    r.acc.push_back(a);
    r.gyro.push_back(g);
  }
  r.rate_hz = static_cast<double>(r.acc.size() - 1) / (t - t0);
  return r;
}

// The variance of the angle (velocity) that a filter's midpoint integration
// accumulates over windows of `m` steps of the still record, its mean
// removed: what the filter's propagated covariance should equal.
double WindowIntegralVariance(const std::vector<std::array<double, 3>>& x,
                              int axis,
                              int m,
                              double dt) {
  double mean = 0.0;
  for (const auto& v : x) mean += v[axis];
  mean /= static_cast<double>(x.size());
  std::vector<double> sums;
  for (std::size_t start = 0; start + m < x.size(); start += m) {
    double s = 0.0;
    for (int k = 0; k < m; ++k) {
      s += 0.5 * (x[start + k][axis] + x[start + k + 1][axis] - 2.0 * mean) * dt;
    }
    sums.push_back(s);
  }
  double ss = 0.0;
  for (double s : sums) ss += s * s;
  return ss / static_cast<double>(sums.size());
}

double LargestWindowVariance(const std::vector<std::array<double, 3>>& x,
                             int m,
                             double dt) {
  double v = 0.0;
  for (int i = 0; i < 3; ++i) v = std::max(v, WindowIntegralVariance(x, i, m, dt));
  return v;
}

// A key's number in a written file ("key: 1.0e-3  # ..."); NaN if absent.
double KeyValue(const std::string& text, const std::string& key) {
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const auto at = line.find(key + ":");
    if (at == std::string::npos || line[0] == '#') continue;
    return std::stod(line.substr(at + key.size() + 1));
  }
  return std::nan("");
}

std::vector<double> KeyTriple(const std::string& text, const std::string& key) {
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#' || line.find(key + ":") == std::string::npos)
      continue;
    std::string inner = line.substr(line.find('[') + 1);
    inner = inner.substr(0, inner.find(']'));
    std::replace(inner.begin(), inner.end(), ',', ' ');
    std::istringstream s(inner);
    std::vector<double> v;
    for (double d; s >> d;) v.push_back(d);
    return v;
  }
  return {};
}

ExportedFile ExportNoise(const std::string& format,
                         const Calibration* calibration = nullptr) {
  static const NoiseFile noise = ReadNoiseFile(TestDataPath("noise_still.json"));
  ExportSources s;
  s.noise = &noise;
  s.noise_path = "noise_still.json";
  s.calibration = calibration;
  s.calibration_path = "calib.json";
  const ExportFormat* f = FindExportFormat(format);
  EXPECT_NE(f, nullptr) << format;
  return Export(*f, s, ExportOptions{});
}

// A window of 1 s: white noise dominates it in this record, and 180 windows
// estimate each variance to about ±11 % (1σ); the largest of three axes is
// compared with the file's one value (the largest axis), so ±30 %.
constexpr int kWindowSteps = 25;
constexpr double kLo = 0.7, kHi = 1.3;

// ORB-SLAM3 (Tracking.cc: IMU::Calib(Tbc, Ng*sf, Na*sf, Ngw/sf, Naw/sf),
// sf = sqrt(IMU.Frequency); ImuTypes.cc Preintegrated::IntegrateNewMeasurement:
// C = A C A' + B Nga B', B's rotation block Jr*dt, Nga = (Ng*sf)^2): at rest,
// the rotation variance after m steps is m * dt^2 * Ng^2 * f.
TEST(FilterNoise, OrbSlam3PropagatesTheRecordsScatter) {
  const StillRecord r = ReadStill();
  const ExportedFile f = ExportNoise("orb-slam3");
  EXPECT_EQ(f.text.rfind("%YAML:1.0\n", 0), 0U);
  const double ng = KeyValue(f.text, "IMU.NoiseGyro");
  const double na = KeyValue(f.text, "IMU.NoiseAcc");
  const double freq = KeyValue(f.text, "IMU.Frequency");
  EXPECT_EQ(freq, 25.0);
  const double dt = 1.0 / freq;
  const double sf = std::sqrt(freq);
  const double rot = kWindowSteps * dt * dt * (ng * sf) * (ng * sf);
  const double vel = kWindowSteps * dt * dt * (na * sf) * (na * sf);
  const double rot_data = LargestWindowVariance(r.gyro, kWindowSteps, dt);
  const double vel_data = LargestWindowVariance(r.acc, kWindowSteps, dt);
  EXPECT_GT(rot / rot_data, kLo);
  EXPECT_LT(rot / rot_data, kHi);
  EXPECT_GT(vel / vel_data, kLo);
  EXPECT_LT(vel / vel_data, kHi);
}

// VINS (integration_base.h midPointIntegration: V's rotation blocks 0.5*dt
// for each of the step's two gyroscope noises, noise = GYR_N^2; the same for
// the velocity and ACC_N): at rest the rotation variance after m steps is
// m * 2 * (0.5 dt)^2 * gyr_n^2.
TEST(FilterNoise, VinsPropagatesTheRecordsScatter) {
  const StillRecord r = ReadStill();
  const ExportedFile f = ExportNoise("vins");
  const double gyr_n = KeyValue(f.text, "gyr_n");
  const double acc_n = KeyValue(f.text, "acc_n");
  const double dt = 1.0 / r.rate_hz;
  const double rot = kWindowSteps * 2.0 * 0.25 * dt * dt * gyr_n * gyr_n;
  const double vel = kWindowSteps * 2.0 * 0.25 * dt * dt * acc_n * acc_n;
  const double rot_data = LargestWindowVariance(r.gyro, kWindowSteps, dt);
  const double vel_data = LargestWindowVariance(r.acc, kWindowSteps, dt);
  EXPECT_GT(rot / rot_data, kLo);
  EXPECT_LT(rot / rot_data, kHi);
  EXPECT_GT(vel / vel_data, kLo);
  EXPECT_LT(vel / vel_data, kHi);
  // The bias walk per step, acc_w*dt, is Kalibr's discrete K*sqrt(dt).
  const NoiseFile noise = ReadNoiseFile(TestDataPath("noise_still.json"));
  const KalibrFile k = KalibrYaml(noise.result, noise.input, "");
  EXPECT_NEAR(
      KeyValue(f.text, "acc_w") * dt / (k.accel_random_walk.value * std::sqrt(dt)),
      1.0,
      1e-5);
}

// KF-GINS (kf_gins.cpp loadConfig: arw * D2R / 60 rad/sqrt(s), vrw / 60
// m/s/sqrt(s); gi_engine.cpp: Qc = arw^2, continuous): the angle variance
// over T seconds is arw^2 * T, per axis.
TEST(FilterNoise, KfGinsPropagatesEachAxissScatter) {
  const StillRecord r = ReadStill();
  const ExportedFile f = ExportNoise("kf-gins");
  const std::vector<double> arw = KeyTriple(f.text, "arw");
  const std::vector<double> vrw = KeyTriple(f.text, "vrw");
  ASSERT_EQ(arw.size(), 3U);
  ASSERT_EQ(vrw.size(), 3U);
  const double dt = 1.0 / r.rate_hz;
  for (int i = 0; i < 3; ++i) {
    const double arw_si = arw[i] * kPi / 180.0 / 60.0;
    const double vrw_si = vrw[i] / 60.0;
    const double t = kWindowSteps * dt;
    // One axis: ±11 % (1σ) from 180 windows.
    EXPECT_NEAR(arw_si * arw_si * t / WindowIntegralVariance(r.gyro, i, kWindowSteps, dt),
                1.0,
                0.35)
        << i;
    EXPECT_NEAR(vrw_si * vrw_si * t / WindowIntegralVariance(r.acc, i, kWindowSteps, dt),
                1.0,
                0.35)
        << i;
  }
  // KF-GINS reads the block with yaml-cpp (kf_gins.cpp loadConfig): every
  // key a vector of three, corrtime a number.
  const YAML::Node config = YAML::Load(f.text);
  for (const char* key : {"arw", "vrw", "gbstd", "abstd", "gsstd", "asstd"}) {
    EXPECT_EQ(config["imunoise"][key].as<std::vector<double>>().size(), 3U) << key;
  }
  EXPECT_GT(config["imunoise"]["corrtime"].as<double>(), 0.0);
  // Three minutes show no random walk: the correlation time rests on a bound.
  EXPECT_THAT(f.text, HasSubstr("# corrtime NOT MEASURED: no axis shows both B and K"));
  EXPECT_THAT(f.text, HasSubstr("# gsstd NOT MEASURED"));
  bool corrtime_noted = false;
  for (const auto& n : f.notes) corrtime_noted |= n.quantity == "corrtime";
  EXPECT_TRUE(corrtime_noted);
}

// KF-GINS's Gauss-Markov bias (gi_engine.cpp: process noise 2 sigma^2 / T,
// decay 1/T) walks at times short against T with density sqrt(2/T) sigma:
// the file's corrtime makes it the measured random walk K of the axis it
// names, from the shortest T = 2B^2/K^2.
TEST(FilterNoise, KfGinsCorrelationTimeGivesTheRandomWalk) {
  NoiseFile noise = ReadNoiseFile(TestDataPath("noise_still.json"));
  const double b[3] = {2e-4, 3e-4, 5e-4},
               k[3] = {4e-6, 3e-6, 2e-6};  // rad/s, rad/s^2/sqrt(Hz)
  for (int i = 0; i < 3; ++i) {
    TermEstimate& bi = noise.result.gyro_radps->axes[i].terms[2];
    TermEstimate& ki = noise.result.gyro_radps->axes[i].terms[3];
    bi.status = ki.status = TermStatus::kMeasured;
    bi.value = b[i];
    ki.value = k[i];
  }
  ExportSources s;
  s.noise = &noise;
  const ExportedFile f = Export(*FindExportFormat("kf-gins"), s, ExportOptions{});
  const double t_s = KeyValue(f.text, "  corrtime") * 3600.0;
  // Shortest T: x, 2 (2e-4)^2 / (4e-6)^2 = 5000 s.
  EXPECT_NEAR(t_s, 5000.0, 0.01);
  EXPECT_THAT(f.text, HasSubstr("from the gyroscope x axis"));
  const double sigma = KeyTriple(f.text, "gbstd")[0] * kPi / 180.0 / 3600.0;
  EXPECT_NEAR(std::sqrt(2.0 * sigma * sigma / t_s), k[0], 1e-5 * k[0]);
}

// sensor_msgs/Imu: the diagonal is the variance of one sample, per axis.
TEST(FilterNoise, RosCovarianceIsEachAxissSampleVariance) {
  const StillRecord r = ReadStill();
  const ExportedFile f = ExportNoise("ros-imu");
  const std::vector<double> gc = KeyTriple(f.text, "angular_velocity_covariance");
  const std::vector<double> ac = KeyTriple(f.text, "linear_acceleration_covariance");
  ASSERT_EQ(gc.size(), 9U);
  ASSERT_EQ(ac.size(), 9U);
  EXPECT_EQ(KeyTriple(f.text, "orientation_covariance")[0], -1.0);
  for (int i = 0; i < 3; ++i) {
    double mg = 0, ma = 0;
    for (std::size_t k = 0; k < r.gyro.size(); ++k) {
      mg += r.gyro[k][i];
      ma += r.acc[k][i];
    }
    mg /= r.gyro.size();
    ma /= r.acc.size();
    double vg = 0, va = 0;
    for (std::size_t k = 0; k < r.gyro.size(); ++k) {
      vg += (r.gyro[k][i] - mg) * (r.gyro[k][i] - mg);
      va += (r.acc[k][i] - ma) * (r.acc[k][i] - ma);
    }
    vg /= r.gyro.size();
    va /= r.acc.size();
    // 4500 samples: ±2 % (1σ); the fitted N, a few per cent more.
    EXPECT_NEAR(gc[4 * i] / vg, 1.0, 0.12) << i;
    EXPECT_NEAR(ac[4 * i] / va, 1.0, 0.12) << i;
    EXPECT_EQ(gc[4 * i + 1 - (i == 2 ? 2 : 0)], 0.0);
  }
}

// Three minutes cannot show a random walk: ORB-SLAM3's and VINS's walk lines
// are bounds, each said on its own line before the key.
TEST(FilterNoise, UpperBoundsSaidOnTheirOwnLine) {
  for (const char* format : {"orb-slam3", "vins"}) {
    const ExportedFile f = ExportNoise(format);
    const std::string key = std::string(format) == "vins" ? "acc_w" : "IMU.AccWalk";
    EXPECT_THAT(f.text, HasSubstr("# " + key + " NOT MEASURED: the upper bound"))
        << format;
    bool noted = false;
    for (const auto& n : f.notes)
      noted |= n.quantity == key && n.kind == ExportNoteKind::kUpperBound;
    EXPECT_TRUE(noted) << format;
  }
}

// --- Autopilots -----------------------------------------------------------

// The Xsens calibration of tests/data (its real angles), taken as if it had
// been made from an autopilot's m/s² readings.
Calibration XsensInMps2() {
  Calibration c = ReadCalibrationFile(TestDataPath("xsens_imu_half1.json"));
  c.input_units = AccelUnits::kMps2;
  c.mps2_per_unit = 1.0;
  c.model.bias_mps2 = Eigen::Vector3d(0.12, -0.08, 0.21);
  c.scale_reference.clear();
  c.input_layout.reset();
  if (c.gyroscope) {
    c.gyroscope->input_units = GyroUnits::kRadps;
    c.gyroscope->radps_per_unit = 1.0;
    c.gyroscope->bias_radps = Eigen::Vector3d(0.003, -0.002, 0.001);
  }
  return c;
}

std::map<std::string, double> Parameters(const std::string& text, bool px4) {
  std::map<std::string, double> p;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> fields;
    std::string field;
    std::istringstream fs(line);
    while (std::getline(fs, field, px4 ? '\t' : ',')) fields.push_back(field);
    if (px4) {
      EXPECT_EQ(fields.size(), 5U) << line;
      EXPECT_EQ(fields[4], "9") << line;
      p[fields[2]] = std::stod(fields[3]);
    } else {
      EXPECT_EQ(fields.size(), 2U) << line;
      p[fields[0]] = std::stod(fields[1]);
    }
  }
  return p;
}

// Readings y = Forward(a) of specific forces a of magnitude g over the
// sphere, as the sensor gives them.
std::vector<Eigen::Vector3d> Readings(const Calibration& c) {
  std::vector<Eigen::Vector3d> y;
  for (int i = 0; i < 400; ++i) {
    const double z = 1.0 - 2.0 * (i + 0.5) / 400.0;
    const double r = std::sqrt(1.0 - z * z);
    const double phi = 2.399963 * i;
    y.push_back(c.model.Forward(
        c.gravity_mps2 * Eigen::Vector3d(r * std::cos(phi), r * std::sin(phi), z)));
  }
  return y;
}

ExportedFile ExportAutopilot(const std::string& format, const Calibration& c) {
  ExportSources s;
  s.calibration = &c;
  s.calibration_path = "xsens_mps2.json";
  return Export(*FindExportFormat(format), s, ExportOptions{});
}

// PX4 (Accelerometer.hpp Correct: (data - offset).emult(scale)) and
// ArduPilot (_rotate_and_correct_accel: accel -= offset; accel.x *=
// scale.x ...), applied to the same raw readings as mpcal's correction.
void CheckAutopilotFormula(const std::string& format, bool px4) {
  const std::string off = px4 ? "CAL_ACC0_{}OFF" : "INS_ACCOFFS_{}";
  const char* axes[] = {"X", "Y", "Z"};
  const auto name = [&](const char* pattern, int i) {
    std::string s = pattern;
    return s.replace(s.find("{}"), 2, axes[i]);
  };
  // A 6-parameter calibration: the autopilot's model holds it, to rounding.
  Calibration six = XsensInMps2();
  six.model_kind = ModelKind::kBiasScale6;
  six.model.theta_yz_rad = six.model.theta_zx_rad = six.model.theta_zy_rad = 0.0;
  // The 9-parameter one: the difference is what the file says it drops.
  const Calibration nine = XsensInMps2();
  for (const Calibration* c : std::array<const Calibration*, 2>{&six, &nine}) {
    const ExportedFile f = ExportAutopilot(format, *c);
    const auto p = Parameters(f.text, px4);
    double worst = 0.0;
    for (const Eigen::Vector3d& y : Readings(*c)) {
      Eigen::Vector3d ap;
      for (int i = 0; i < 3; ++i) {
        ap[i] = (y[i] - p.at(name(off.c_str(), i))) *
                p.at(name(px4 ? "CAL_ACC0_{}SCALE" : "INS_ACCSCAL_{}", i));
      }
      worst = std::max(worst, (ap - c->Correct(y)).norm());
    }
    const AutopilotLoss loss = AutopilotModelLoss(*c);
    if (c == &six) {
      EXPECT_LT(worst, 1e-6) << format;  // 9 significant digits
      EXPECT_LT(loss.accel_max_error_mps2, 1e-12);
    } else {
      // The readings cover the sphere more coarsely than the loss's search.
      EXPECT_LE(worst, loss.accel_max_error_mps2 * (1 + 1e-6)) << format;
      EXPECT_GT(worst, 0.95 * loss.accel_max_error_mps2) << format;
      EXPECT_GT(loss.accel_max_error_mps2, 0.1) << format;  // zx = -0.021 rad: 0.2 m/s²
      char said[64];
      std::snprintf(said, sizeof said, "up to %.3g m/s^2", loss.accel_max_error_mps2);
      EXPECT_THAT(f.text, HasSubstr(said)) << format;
    }
    // The gyroscope: reading - offset (Gyroscope.hpp; _rotate_and_correct_gyro).
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(p.at(name(px4 ? "CAL_GYRO0_{}OFF" : "INS_GYROFFS_{}", i)),
                  c->gyroscope->bias_radps[i],
                  1e-9);
    }
  }
}

TEST(AutopilotParameters, Px4FormulaMatchesMpcal) { CheckAutopilotFormula("px4", true); }
TEST(AutopilotParameters, ArduPilotFormulaMatchesMpcal) {
  CheckAutopilotFormula("ardupilot", false);
}

// Import, then export: the parameter lines come back as they were.
TEST(AutopilotParameters, ImportExportRoundTrip) {
  for (const char* format : {"px4", "ardupilot"}) {
    const bool px4 = std::string(format) == "px4";
    const ExportedFile first = ExportAutopilot(format, XsensInMps2());
    const ImportedCalibration imported = Import(
        *FindExportFormat(format), {ImportFile{"params", first.text}}, ImportOptions{});
    const Calibration& c = imported.calibration;
    EXPECT_EQ(c.model_kind, ModelKind::kBiasScale6);
    EXPECT_FALSE(c.std.has_value());
    ASSERT_TRUE(c.gyroscope.has_value());
    EXPECT_FALSE(c.gyroscope->m_covariance.has_value());
    const Calibration original = XsensInMps2();
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(c.model.bias_mps2[i], original.model.bias_mps2[i], 1e-8);
      EXPECT_NEAR(
          c.model.scale_factor_error[i], original.model.scale_factor_error[i], 1e-8);
    }
    const ExportedFile second = ExportAutopilot(format, c);
    EXPECT_EQ(Parameters(second.text, px4), Parameters(first.text, px4)) << format;
  }
}

// ArduPilot reads 100 characters at a time: no line reaches it, whatever the
// path of the calibration.
TEST(AutopilotParameters, ArduPilotLinesFitItsReader) {
  const Calibration c = XsensInMps2();
  ExportSources s;
  s.calibration = &c;
  s.calibration_path = std::string(300, 'd') + "/calib.json";
  const ExportedFile f = Export(*FindExportFormat("ardupilot"), s, ExportOptions{});
  std::istringstream in(f.text);
  std::string line;
  while (std::getline(in, line)) EXPECT_LT(line.size(), 99U) << line;
}

TEST(AutopilotParameters, RawCountsRefused) {
  const Calibration c = ReadCalibrationFile(TestDataPath("xsens_imu_half1.json"));
  ExportSources s;
  s.calibration = &c;
  s.calibration_path = "xsens.json";
  try {
    Export(*FindExportFormat("px4"), s, ExportOptions{});
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kUnits);
    EXPECT_THAT(e.what(), HasSubstr("raw counts"));
  }
}

void ExpectImportError(const char* format,
                       const std::string& text,
                       const std::string& what) {
  try {
    Import(*FindExportFormat(format), {ImportFile{"bad.params", text}}, ImportOptions{});
    FAIL() << "no error for: " << text;
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr(what)) << text;
    EXPECT_THAT(e.what(), HasSubstr("bad.params"));
  }
}

TEST(AutopilotParameters, BadFilesGetOneError) {
  const std::string ap =
      "INS_ACCOFFS_X,0.1\nINS_ACCOFFS_Y,0.1\nINS_ACCOFFS_Z,0.1\n"
      "INS_ACCSCAL_X,1.01\nINS_ACCSCAL_Y,0.99\n";
  ExpectImportError("ardupilot", ap, "no INS_ACCSCAL_Z");
  ExpectImportError("ardupilot", ap + "INS_ACCSCAL_Z,0\n", "a scale is positive");
  ExpectImportError("ardupilot",
                    ap + "INS_ACCSCAL_Z,abc\n",
                    "line 6: INS_ACCSCAL_Z has the value 'abc'");
  ExpectImportError("ardupilot", ap + "INS_ACCSCAL_Z,nan\n", "not a finite number");
  ExpectImportError(
      "ardupilot", "INS_ACCSCAL_Z\n", "line 1: not an ArduPilot parameter line");
  // A Kalibr camera chain is not a parameter file.
  ExpectImportError(
      "px4", "cam0:\n  camera_model: pinhole\n", "line 1: not a QGroundControl");
  ExpectImportError("px4", "1\t1\tCAL_ACC0_XOFF\t0.1\n", "line 1: not a QGroundControl");
}

}  // namespace
}  // namespace mpcal
