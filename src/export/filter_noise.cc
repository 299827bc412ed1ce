// The noise of a still record in the files of ORB-SLAM3, VINS, KF-GINS and
// sensor_msgs/Imu (filter_formats.h). The one value per sensor that
// ORB-SLAM3 and VINS take is KalibrYaml's (the largest axis), so that every
// file of a record says the same.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "export/filter_formats.h"
#include "mpcal/error.h"
#include "mpcal/noise_file.h"

namespace mpcal::export_formats {

namespace {

constexpr const char* kFilterAxisNames[] = {"x", "y", "z"};
constexpr double kRadToDeg = 180.0 / std::numbers::pi;

// A comment's text cannot break out of its line.
std::string FilterCommentLine(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  std::replace(text.begin(), text.end(), '\r', ' ');
  return "# " + text + "\n";
}

std::string RecordText(const NoiseResult& r, const std::string& input) {
  return fmt::format(
      "measured by mpcal {} from '{}' ({} at {:.6g} Hz, overlapping "
      "Allan deviation).",
      MPCAL_VERSION,
      input,
      FormatRecordLength(r.record_s),
      r.rate_hz);
}

// How the values relate to the record: as measured, or inflated by the
// user's factor (then each value's comment gives the record's own).
std::string InflationLine(double inflate) {
  if (inflate == 1.0) return "measured, not inflated.";
  return fmt::format(
      "INFLATED x{:g} at the user's request: each noise value below is "
      "{:g} times the record's, which its comment gives.",
      inflate,
      inflate);
}

// The line that says a value is not a measurement, before its key.
std::string BoundLine(const std::string& key, const KalibrValue& v) {
  std::string s = fmt::format(
      "{} NOT MEASURED: the upper bound from a record too short to show it", key);
  if (v.record_needed_s) {
    s += fmt::format(" (record at least {} to measure it)",
                     FormatRecordLength(*v.record_needed_s));
  }
  return FilterCommentLine(s);
}

struct OneValue {
  const char* key;
  const KalibrValue* value;
  double factor;  // from mpcal's continuous density to the tool's value
  const char* unit;
};

void AppendOneValues(std::string& out,
                     ExportedFile& file,
                     const KalibrFile& k,
                     const OneValue* values,
                     int count) {
  for (int i = 0; i < count; ++i) {
    const OneValue& v = values[i];
    if (v.value->upper_bound) {
      out += BoundLine(v.key, *v.value);
      file.notes.push_back(ExportNote{ExportNoteKind::kUpperBound,
                                      v.key,
                                      k.Written(*v.value) * v.factor,
                                      v.unit,
                                      v.value->record_needed_s});
    }
    out += fmt::format("{}: {:.6e}  # {}, axis {}{}\n",
                       v.key,
                       k.Written(*v.value) * v.factor,
                       v.unit,
                       kFilterAxisNames[v.value->axis],
                       k.inflate == 1.0
                           ? std::string()
                           : fmt::format("; INFLATED x{:g}: the record's {:.6e}",
                                         k.inflate,
                                         v.value->value * v.factor));
  }
}

ExportedFile WriteOrbSlam3(const ExportSources& s, const ExportOptions& o) {
  const NoiseResult& r = s.noise->result;
  const std::string& input = s.noise->input;
  const KalibrFile k = KalibrYaml(r, input, "", o.inflate);
  ExportedFile f;
  std::string& t = f.text;
  t = "%YAML:1.0\n";
  t += FilterCommentLine("ORB-SLAM3 IMU noise, " + RecordText(r, input));
  for (const char* line : {
           "Paste these keys into the ORB-SLAM3 settings file; IMU.T_b_c1 (the camera",
           "to IMU transform) comes from a camera-IMU calibration, not from mpcal.",
           "Continuous-time densities, as ORB-SLAM3 reads them (Settings.cc readIMU;",
           "Tracking.cc builds IMU::Calib with noise*sqrt(f) and walk/sqrt(f)).",
           "Rule across axes: the largest measured of x, y, z.",
       }) {
    t += FilterCommentLine(line);
  }
  t += FilterCommentLine(InflationLine(k.inflate));
  const OneValue values[] = {
      {"IMU.NoiseGyro", &k.gyro_noise_density, 1.0, "rad/s/sqrt(Hz)"},
      {"IMU.NoiseAcc", &k.accel_noise_density, 1.0, "m/s^2/sqrt(Hz)"},
      {"IMU.GyroWalk", &k.gyro_random_walk, 1.0, "rad/s^2/sqrt(Hz)"},
      {"IMU.AccWalk", &k.accel_random_walk, 1.0, "m/s^3/sqrt(Hz)"},
  };
  AppendOneValues(t, f, k, values, 4);
  t += fmt::format("IMU.Frequency: {}  # Hz ({:.6g} Hz measured, rounded)\n",
                   static_cast<long long>(std::lround(r.rate_hz)),
                   r.rate_hz);
  return f;
}

ExportedFile WriteVins(const ExportSources& s, const ExportOptions& o) {
  const NoiseResult& r = s.noise->result;
  const std::string& input = s.noise->input;
  const KalibrFile k = KalibrYaml(r, input, "", o.inflate);
  ExportedFile f;
  std::string& t = f.text;
  const double root_f = std::sqrt(r.rate_hz);
  t = "%YAML:1.0\n";
  t += FilterCommentLine("VINS-Mono / VINS-Fusion IMU noise, " + RecordText(r, input));
  for (const std::string& line : {
           std::string(
               "Paste these keys into the VINS config file (read by parameters.cpp)."),
           std::string(
               "VINS takes them per sample, not as densities: integration_base.h adds"),
           std::string(
               "each of a step's two samples' noise with weight dt/2 and the bias walk"),
           std::string(
               "with weight dt. So that its covariance grows as this sensor's does:"),
           fmt::format(
               "acc_n = N*sqrt(2f), acc_w = K*sqrt(f), f = {:.6g} Hz (gyr_ alike).",
               r.rate_hz),
           fmt::format(
               "The standard deviation of one sample is N*sqrt(f): acc {:.4e} m/s^2,",
               k.accel_noise_density.value * root_f),
           fmt::format("gyr {:.4e} rad/s (the record's). Largest measured of x, y, z.",
                       k.gyro_noise_density.value * root_f),
       }) {
    t += FilterCommentLine(line);
  }
  t += FilterCommentLine(InflationLine(k.inflate));
  const double two_f = std::sqrt(2.0 * r.rate_hz);
  const OneValue values[] = {
      {"acc_n", &k.accel_noise_density, two_f, "m/s^2"},
      {"gyr_n", &k.gyro_noise_density, two_f, "rad/s"},
      {"acc_w", &k.accel_random_walk, root_f, "m/s^3 (bias step acc_w*dt per sample)"},
      {"gyr_w", &k.gyro_random_walk, root_f, "rad/s^2 (bias step gyr_w*dt per sample)"},
  };
  AppendOneValues(t, f, k, values, 4);
  return f;
}

// One term of the three axes in a unit of KF-GINS, and whether any is a bound.
struct AxisTriple {
  double v[3] = {0, 0, 0};
  bool bound[3] = {false, false, false};
};

AxisTriple TermOfAxes(const SensorNoise& s, NoiseTerm term, double factor) {
  AxisTriple a;
  for (int i = 0; i < 3; ++i) {
    const TermEstimate& e = s.axes[i].term(term);
    a.bound[i] = !e.value.has_value();
    a.v[i] = (e.value ? *e.value : e.upper_bound) * factor;
  }
  return a;
}

void AppendTriple(std::string& out,
                  ExportedFile& file,
                  const char* key,
                  const AxisTriple& a,
                  const char* unit,
                  const SensorNoise* sensor = nullptr,
                  NoiseTerm term = NoiseTerm::kWhiteNoise,
                  double inflate = 1.0) {
  std::string bounded;
  for (int i = 0; i < 3; ++i) {
    if (a.bound[i])
      bounded += fmt::format("{}{}", bounded.empty() ? "" : ", ", kFilterAxisNames[i]);
  }
  if (!bounded.empty()) {
    out += FilterCommentLine(fmt::format(
        "{} NOT MEASURED on {}: the upper bound from a record too short to show it",
        key,
        bounded));
    file.notes.push_back(ExportNote{
        ExportNoteKind::kUpperBound,
        key,
        std::max({a.v[0], a.v[1], a.v[2]}),
        unit,
        sensor ? sensor->record_needed_s[static_cast<int>(term)] : std::nullopt});
  }
  out += fmt::format(
      "  {}: [{:.6g}, {:.6g}, {:.6g}]  # [{}]{}\n",
      key,
      a.v[0],
      a.v[1],
      a.v[2],
      unit,
      inflate == 1.0
          ? std::string()
          : fmt::format("; INFLATED x{:g}: the record's [{:.6g}, {:.6g}, {:.6g}]",
                        inflate,
                        a.v[0] / inflate,
                        a.v[1] / inflate,
                        a.v[2] / inflate));
}

// The correlation time T = 2B²/K² (s) of the axes where both terms were
// measured: the shortest, the one whose process noise is largest.
struct CorrTime {
  double seconds = 0.0;
  bool gyro = false;
  int axis = 0;
};

void ShortestCorrTime(const SensorNoise& s, bool gyro, std::optional<CorrTime>& best) {
  for (int i = 0; i < 3; ++i) {
    const TermEstimate& b = s.axes[i].term(NoiseTerm::kBiasInstability);
    const TermEstimate& k = s.axes[i].term(NoiseTerm::kRandomWalk);
    if (!b.value || !k.value || !(*b.value > 0.0) || !(*k.value > 0.0)) continue;
    const double t = 2.0 * *b.value * *b.value / (*k.value * *k.value);
    if (!best || t < best->seconds) best = CorrTime{t, gyro, i};
  }
}

// gsstd and asstd: the scale factors' change over time is not in a still
// record; the calibration's 1σ of the scale factors when given, else
// KF-GINS's example value, each said so.
void AppendScaleLines(std::string& t, ExportedFile& f, const Calibration* calibration) {
  AxisTriple gs, as;
  std::string scale_source = "KF-GINS's example value (config/kf-gins.yaml)";
  for (int i = 0; i < 3; ++i) {
    gs.v[i] = as.v[i] = 1000.0;
  }
  if (calibration && calibration->std) {
    scale_source = "the calibration's 1 sigma of the scale factor";
    for (int i = 0; i < 3; ++i) as.v[i] = calibration->std->scale_factor_error[i] * 1e6;
    if (calibration->gyroscope && calibration->gyroscope->m_covariance) {
      const Eigen::Matrix3d m_std = calibration->gyroscope->MStd();
      for (int i = 0; i < 3; ++i) gs.v[i] = m_std(i, i) * 1e6;
    }
  }
  for (const char* key : {"gsstd", "asstd"}) {
    t += FilterCommentLine(fmt::format(
        "{} NOT MEASURED: the scale factor's instability is not in a still record; "
        "written: {}",
        key,
        scale_source));
    const AxisTriple& v = std::string(key) == "gsstd" ? gs : as;
    f.notes.push_back(ExportNote{ExportNoteKind::kNotMeasured,
                                 key,
                                 std::max({v.v[0], v.v[1], v.v[2]}),
                                 "ppm",
                                 std::nullopt});
    AppendTriple(t, f, key, v, "ppm");
  }
}

// corrtime: the shortest T of the axes that show both B and K.
void AppendCorrTime(std::string& t,
                    ExportedFile& f,
                    const SensorNoise& g,
                    const SensorNoise& a) {
  std::optional<CorrTime> ct;
  ShortestCorrTime(g, true, ct);
  ShortestCorrTime(a, false, ct);
  if (ct) {
    t += fmt::format("  corrtime: {:.6g}  # [hr], the shortest, from the {} {} axis\n",
                     ct->seconds / 3600.0,
                     ct->gyro ? "gyroscope" : "accelerometer",
                     kFilterAxisNames[ct->axis]);
  } else {
    // A bound of B or K would give a bound of T in one direction only: no
    // value of the record's; KF-GINS's own example value, said so.
    t += FilterCommentLine(
        "corrtime NOT MEASURED: no axis shows both B and K; written: KF-GINS's example "
        "value (config/kf-gins.yaml)");
    ExportNote note{ExportNoteKind::kNotMeasured, "corrtime", 1.0, "h", std::nullopt};
    note.record_could_show = true;  // with B and K measured on one axis
    f.notes.push_back(note);
    t += "  corrtime: 1.0  # [hr]\n";
  }
}

ExportedFile WriteKfGins(const ExportSources& s, const ExportOptions& o) {
  const NoiseResult& r = s.noise->result;
  const std::string& input = s.noise->input;
  if (!r.gyro_radps)
    throw Error("KF-GINS's IMU noise needs a gyroscope; the log has none");
  const SensorNoise& a = r.accel_mps2;
  const SensorNoise& g = *r.gyro_radps;
  ExportedFile f;
  std::string& t = f.text;
  t = FilterCommentLine("KF-GINS IMU noise, " + RecordText(r, input));
  for (const char* line : {
           "Replace the imunoise block of kf-gins.yaml with this one (kf_gins.cpp",
           "loadConfig reads it and converts: arw*D2R/60, vrw/60, gbstd*D2R/3600,",
           "abstd*1e-5, gsstd and asstd *1e-6, corrtime*3600). Per axis x, y, z.",
           "gbstd, abstd: the bias instability B; corrtime: T = 2 B^2 / K^2 (K the",
           "random walk), so that KF-GINS's Gauss-Markov bias (gi_engine.cpp: process",
           "noise 2 sigma^2 / T) walks at short times as this sensor's does.",
       }) {
    t += FilterCommentLine(line);
  }
  if (o.inflate != 1.0) {
    t += FilterCommentLine(InflationLine(o.inflate) +
                           " (arw, vrw, gbstd, abstd; corrtime as measured)");
  }
  t += "imunoise:\n";
  AppendTriple(t,
               f,
               "arw",
               TermOfAxes(g, NoiseTerm::kWhiteNoise, kRadToDeg * 60.0 * o.inflate),
               "deg/sqrt(hr)",
               &g,
               NoiseTerm::kWhiteNoise,
               o.inflate);
  AppendTriple(t,
               f,
               "vrw",
               TermOfAxes(a, NoiseTerm::kWhiteNoise, 60.0 * o.inflate),
               "m/s/sqrt(hr)",
               &a,
               NoiseTerm::kWhiteNoise,
               o.inflate);
  AppendTriple(t,
               f,
               "gbstd",
               TermOfAxes(g, NoiseTerm::kBiasInstability, kRadToDeg * 3600.0 * o.inflate),
               "deg/hr",
               &g,
               NoiseTerm::kBiasInstability,
               o.inflate);
  AppendTriple(t,
               f,
               "abstd",
               TermOfAxes(a, NoiseTerm::kBiasInstability, 1e5 * o.inflate),
               "mGal",
               &a,
               NoiseTerm::kBiasInstability,
               o.inflate);
  AppendScaleLines(t, f, s.calibration);
  AppendCorrTime(t, f, g, a);
  return f;
}

ExportedFile WriteRosImu(const ExportSources& src, const ExportOptions& o) {
  const NoiseResult& r = src.noise->result;
  const std::string& input = src.noise->input;
  if (!r.gyro_radps)
    throw Error("sensor_msgs/Imu covariances need a gyroscope; the log has none");
  ExportedFile f;
  std::string& t = f.text;
  t = FilterCommentLine("sensor_msgs/Imu covariances, " + RecordText(r, input));
  for (const std::string& line : {
           std::string(
               "Row-major 3x3, the variance of one sample of the white noise on the"),
           fmt::format(
               "diagonal: N^2 * f, f = {:.6g} Hz (the rate of the messages; at another",
               r.rate_hz),
           std::string(
               "rate scale by it). The bias is not in them. No orientation estimate:"),
           std::string("orientation_covariance element 0 is -1, as Imu.msg asks."),
       }) {
    t += FilterCommentLine(line);
  }
  if (o.inflate != 1.0) {
    t += FilterCommentLine(
        InflationLine(o.inflate) +
        " (N inflated: the variances are its square times the record's)");
  }
  t += "orientation_covariance: [-1.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0]\n";
  const struct {
    const char* key;
    const SensorNoise* sensor;
    const char* unit;
  } sensors[] = {{"angular_velocity_covariance", &*r.gyro_radps, "(rad/s)^2"},
                 {"linear_acceleration_covariance", &r.accel_mps2, "(m/s^2)^2"}};
  for (const auto& s : sensors) {
    const AxisTriple n = TermOfAxes(*s.sensor, NoiseTerm::kWhiteNoise, o.inflate);
    std::string bounded;
    for (int i = 0; i < 3; ++i) {
      if (n.bound[i])
        bounded += fmt::format("{}{}", bounded.empty() ? "" : ", ", kFilterAxisNames[i]);
    }
    if (!bounded.empty()) {
      t += FilterCommentLine(
          fmt::format("{} NOT MEASURED on {}: an upper bound", s.key, bounded));
      f.notes.push_back(ExportNote{ExportNoteKind::kUpperBound,
                                   s.key,
                                   std::max({n.v[0], n.v[1], n.v[2]}),
                                   s.unit,
                                   std::nullopt});
    }
    double v[3];
    for (int i = 0; i < 3; ++i) v[i] = n.v[i] * n.v[i] * r.rate_hz;
    const double squared = o.inflate * o.inflate;
    t += fmt::format(
        "{}: [{:.6e}, 0.0, 0.0, 0.0, {:.6e}, 0.0, 0.0, 0.0, {:.6e}]  # {}{}\n",
        s.key,
        v[0],
        v[1],
        v[2],
        s.unit,
        o.inflate == 1.0
            ? std::string()
            : fmt::format(
                  "; INFLATED x{:g} (variance x{:g}): the record's [{:.6e}, {:.6e}, "
                  "{:.6e}]",
                  o.inflate,
                  squared,
                  v[0] / squared,
                  v[1] / squared,
                  v[2] / squared));
  }
  return f;
}

ExportFormat NoiseFormat(std::string_view name,
                         std::string_view file,
                         ExportWriter write) {
  ExportFormat f;
  f.name = name;
  f.file = file;
  f.noise = ExportNeed::kRequired;
  f.write = write;
  return f;
}

}  // namespace

ExportFormat OrbSlam3() {
  return NoiseFormat("orb-slam3", "ORB-SLAM3 settings (IMU.*)", WriteOrbSlam3);
}
ExportFormat Vins() {
  return NoiseFormat(
      "vins", "VINS-Mono/VINS-Fusion config (acc_n, gyr_n, acc_w, gyr_w)", WriteVins);
}
ExportFormat KfGins() {
  ExportFormat f = NoiseFormat("kf-gins", "KF-GINS kf-gins.yaml (imunoise)", WriteKfGins);
  // The calibration's 1σ of the scale factors, where KF-GINS wants their
  // instability (not measured either way: said so).
  f.calibration = ExportNeed::kOptional;
  return f;
}
ExportFormat RosImu() {
  return NoiseFormat("ros-imu", "sensor_msgs/Imu covariances", WriteRosImu);
}

}  // namespace mpcal::export_formats
