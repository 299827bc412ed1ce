// Kalibr's IMU YAML (imu.yaml) from a noise analysis: one value per sensor
// and term, the largest measured axis, each line saying where it came from.
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <yaml-cpp/yaml.h>

#include "mpcal/error.h"
#include "mpcal/noise_file.h"

namespace mpcal {
namespace {

constexpr const char* kKalibrAxes[3] = {"x", "y", "z"};
// The largest of the three axes' measured values; only when no axis has one,
// the largest bound. A bound never wins over a measured value: the file's
// value is a measurement whenever there is one, and the comment names the
// axes where there is none.
KalibrValue Largest(const SensorNoise& s, NoiseTerm term, const char* what) {
  KalibrValue best;
  bool any = false;
  bool any_measured = false;
  for (int i = 0; i < 3; ++i) any_measured = any_measured || s.axes[i].term(term).value;
  for (int i = 0; i < 3; ++i) {
    const TermEstimate& e = s.axes[i].term(term);
    const bool bound = !e.value.has_value();
    if (bound && any_measured) continue;
    const double v = bound ? e.upper_bound : *e.value;
    if (!(v > 0.0)) continue;
    if (!any || v > best.value) {
      // The record that shows the term on every axis where it was not seen.
      best = KalibrValue{v,
                         i,
                         bound,
                         bound && e.record_needed_s
                             ? s.record_needed_s[static_cast<int>(term)]
                             : std::nullopt};
      any = true;
    }
  }
  if (!any) throw Error(fmt::format("no {} was measured or bounded on any axis", what));
  return best;
}

std::string Describe(const KalibrValue& v, const SensorNoise& s, NoiseTerm term) {
  std::string per_axis;
  for (int i = 0; i < 3; ++i) {
    const TermEstimate& e = s.axes[i].term(term);
    per_axis += fmt::format("{}{} {}",
                            i ? ", " : "",
                            kKalibrAxes[i],
                            e.value ? fmt::format("{:.4g}", *e.value)
                                    : fmt::format("< {:.4g} ({})",
                                                  e.upper_bound,
                                                  e.status == TermStatus::kDisagrees
                                                      ? "model misses the curve"
                                                      : "not measured"));
  }
  std::string s_out = fmt::format("from axis {} ({})", kKalibrAxes[v.axis], per_axis);
  std::string unmeasured;
  for (int i = 0; i < 3; ++i) {
    if (!v.upper_bound && !s.axes[i].term(term).value)
      unmeasured += fmt::format("{}{}", unmeasured.empty() ? "" : ", ", kKalibrAxes[i]);
  }
  if (!unmeasured.empty()) {
    s_out += fmt::format(
        "; the largest MEASURED axis: not measured on {} (its bound not used)",
        unmeasured);
  }
  if (v.upper_bound && s.axes[v.axis].term(term).status == TermStatus::kDisagrees) {
    s_out +=
        "; NOT MEASURED: the model misses the curve where it dominates; an upper bound "
        "from the curve";
  } else if (v.upper_bound) {
    s_out += "; NOT MEASURED: an upper bound from a record too short to show it";
    if (v.record_needed_s) {
      s_out += fmt::format(", record at least {} to measure it",
                           FormatRecordLength(*v.record_needed_s));
    }
  }
  return s_out;
}

}  // namespace

namespace {

// A comment's text cannot break out of its line: newlines become spaces.
auto YamlComment(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  std::replace(text.begin(), text.end(), '\r', ' ');
  return YAML::Comment(text);
}

// The comment lines that open the Kalibr file, one per line.
void KalibrHeader(YAML::Emitter& y,
                  const NoiseResult& r,
                  const std::string& input,
                  double inflate) {
  y << YamlComment(fmt::format("Kalibr IMU noise model, measured by mpcal {} from '{}'",
                               MPCAL_VERSION,
                               input))
    << YAML::Newline
    << YamlComment(fmt::format("({:.2f} h at {:.6g} Hz, overlapping Allan deviation).",
                               r.record_s / 3600.0,
                               r.rate_hz))
    << YAML::Newline;
  constexpr const char* kDensities[] = {
      "Continuous-time densities, as Kalibr defines them: the discrete noise per",
      "sample is density * sqrt(update_rate), the random-walk step density / "
      "sqrt(update_rate)."};
  constexpr const char* kRule[] = {
      "Rule across axes: the largest of x, y, z (one value per sensor; no axis is",
      "trusted more than it deserves)."};
  constexpr const char* kInflate[] = {
      "Kalibr's wiki advises inflating these for a filter (e.g. x10 the noise "
      "densities)",
      "to cover unmodelled effects; these are the measured values, not inflated."};
  const std::string inflated[] = {
      fmt::format("INFLATED x{:g} at the user's request: each value below is", inflate),
      fmt::format("{:g} times the record's, which its comment gives.", inflate)};
  for (const auto* lines : {kDensities, kRule}) {
    for (int i = 0; i < 2; ++i) y << YamlComment(lines[i]) << YAML::Newline;
  }
  for (int i = 0; i < 2; ++i) {
    y << YamlComment(inflate == 1.0 ? std::string(kInflate[i]) : inflated[i])
      << YAML::Newline;
  }
}

// The model against the curve of a sensor's three axes, on one line.
std::string CheckComment(const SensorNoise& s, bool gyro) {
  std::string out =
      fmt::format("{} model vs Allan curve:", gyro ? "gyroscope" : "accelerometer");
  for (int i = 0; i < 3; ++i) {
    const ModelCheck& c = s.axes[i].check;
    out += fmt::format("{} {} ", i ? "," : "", kKalibrAxes[i]);
    if (c.points == 0) {
      out += "not checked";
      continue;
    }
    out += fmt::format("{} ({} of {} cluster times outside its interval",
                       c.fits ? "fits" : "MISSES",
                       c.outside,
                       c.points);
    if (!c.fits) out += ", at " + FormatTauRanges(c.disagree, 3);
    if (c.excluded > 0) out += fmt::format("; fitted from tau = {:.3g} s", c.from_tau_s);
    out += ")";
  }
  return out;
}

// One value of the Kalibr file, and where it came from.
struct KalibrEntry {
  const char* key;
  const KalibrValue* value;
  const SensorNoise* sensor;
  NoiseTerm term;
  const char* unit;
};

}  // namespace

std::string ValidateInflation(double inflate) {
  if (std::isfinite(inflate) && inflate >= 1.0) return "";
  return fmt::format(
      "the inflation factor is {:g}; it must be a number of at least 1 (1: the "
      "measured values)",
      inflate);
}

KalibrFile KalibrYaml(const NoiseResult& r,
                      const std::string& input,
                      const std::string& topic,
                      double inflate) {
  if (!r.gyro_radps) throw Error("Kalibr's IMU file needs a gyroscope; the log has none");
  if (const std::string why = ValidateInflation(inflate); !why.empty()) {
    throw Error(ErrorKind::kOption, why);
  }
  KalibrFile k;
  k.inflate = inflate;
  const SensorNoise& a = r.accel_mps2;
  const SensorNoise& g = *r.gyro_radps;
  k.accel_noise_density = Largest(a, NoiseTerm::kWhiteNoise, "accelerometer white noise");
  k.accel_random_walk = Largest(a, NoiseTerm::kRandomWalk, "accelerometer random walk");
  k.gyro_noise_density = Largest(g, NoiseTerm::kWhiteNoise, "gyroscope white noise");
  k.gyro_random_walk = Largest(g, NoiseTerm::kRandomWalk, "gyroscope random walk");
  const KalibrEntry entries[] = {
      {"accelerometer_noise_density",
       &k.accel_noise_density,
       &a,
       NoiseTerm::kWhiteNoise,
       "m/s^2/sqrt(Hz)"},
      {"accelerometer_random_walk",
       &k.accel_random_walk,
       &a,
       NoiseTerm::kRandomWalk,
       "m/s^3/sqrt(Hz)"},
      {"gyroscope_noise_density",
       &k.gyro_noise_density,
       &g,
       NoiseTerm::kWhiteNoise,
       "rad/s/sqrt(Hz)"},
      {"gyroscope_random_walk",
       &k.gyro_random_walk,
       &g,
       NoiseTerm::kRandomWalk,
       "rad/s^2/sqrt(Hz)"},
  };
  // yaml-cpp quotes and escapes what needs it: a topic with a newline, a '#'
  // or a ':' stays one value.
  YAML::Emitter y;
  KalibrHeader(y, r, input, inflate);
  for (const bool gyro : {false, true}) {
    y << YamlComment(CheckComment(gyro ? g : a, gyro)) << YAML::Newline;
  }
  for (const KalibrEntry& e : entries) {
    if (&e != &entries[0]) y << YAML::Newline;
    y << YamlComment(fmt::format("{} {}", e.key, Describe(*e.value, *e.sensor, e.term)));
  }
  y << YAML::BeginMap;
  for (const KalibrEntry& e : entries) {
    std::string note =
        fmt::format("{}{}", e.value->upper_bound ? "UPPER BOUND, " : "", e.unit);
    if (inflate != 1.0) {
      note += fmt::format(", INFLATED x{:g}: the record's {} {:.6e}",
                          inflate,
                          e.value->upper_bound ? "upper bound" : "measured value",
                          e.value->value);
    }
    y << YAML::Key << e.key << YAML::Value << fmt::format("{:.6e}", k.Written(*e.value))
      << YamlComment(note);
  }
  y << YAML::Key << "rostopic" << YAML::Value << YAML::DoubleQuoted << topic;
  y << YAML::Key << "update_rate" << YAML::Value << fmt::format("{:.6g}", r.rate_hz)
    << YamlComment("Hz");
  y << YAML::EndMap;
  if (!y.good()) {
    throw Error("Kalibr's IMU file could not be written: " + y.GetLastError());
  }
  k.text = std::string(y.c_str()) + "\n";
  return k;
}

}  // namespace mpcal
