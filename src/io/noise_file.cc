// The noise analysis's JSON (writer and reader).
#include "mpcal/noise_file.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "io/json_reader.h"
#include "io/json_text.h"
#include "mpcal/error.h"

namespace mpcal {
namespace {

using json = nlohmann::ordered_json;
constexpr const char* kFormat = "mpcal.noise/1";
constexpr const char* kAxisNames[3] = {"x", "y", "z"};

const char* SensorUnitKey(bool gyroscope) { return gyroscope ? "radps" : "mps2"; }

json TermJson(const TermEstimate& e) {
  json j;
  j["status"] = std::string(ToString(e.status));
  if (e.value) {
    j["value"] = *e.value;
    j["lo"] = e.lo;
    j["hi"] = e.hi;
    j["tau_range_s"] = {e.tau_lo_s, e.tau_hi_s};
  } else {
    j["upper_bound"] = e.upper_bound;
    j["record_needed_s"] = e.record_needed_s ? json(*e.record_needed_s) : json(nullptr);
  }
  return j;
}

// The status and, when measured, the interval of an extra term; `value`,
// `lo`, `hi` its named figures ({key, value} pairs in order).
using Figures = std::vector<std::pair<std::string, double>>;

json ExtraTermJson(TermStatus status,
                   bool modelled,
                   bool measured,
                   const Figures& figures,
                   double tau_lo_s,
                   double tau_hi_s) {
  json j;
  j["status"] = std::string(ToString(status));
  j["modelled"] = modelled;
  if (measured) {
    for (const auto& [key, v] : figures) j[key] = v;
    j["tau_range_s"] = {tau_lo_s, tau_hi_s};
  }
  return j;
}

json GaussMarkovJson(const GaussMarkovTerm& g, const std::string& u) {
  return ExtraTermJson(g.status,
                       g.modelled,
                       g.sigma.has_value(),
                       {{"sigma_" + u, g.sigma.value_or(0.0)},
                        {"sigma_lo_" + u, g.sigma_lo},
                        {"sigma_hi_" + u, g.sigma_hi},
                        {"tau_c_s", g.tau_c_s},
                        {"tau_c_lo_s", g.tau_c_lo_s},
                        {"tau_c_hi_s", g.tau_c_hi_s}},
                       g.tau_lo_s,
                       g.tau_hi_s);
}

json SinusoidJson(const SinusoidTerm& s, const std::string& u) {
  return ExtraTermJson(s.status,
                       s.modelled,
                       s.amplitude.has_value(),
                       {{"amplitude_" + u, s.amplitude.value_or(0.0)},
                        {"amplitude_lo_" + u, s.amplitude_lo},
                        {"amplitude_hi_" + u, s.amplitude_hi},
                        {"period_s", s.period_s},
                        {"period_lo_s", s.period_lo_s},
                        {"period_hi_s", s.period_hi_s}},
                       s.tau_lo_s,
                       s.tau_hi_s);
}

json CheckJson(const ModelCheck& c) {
  json j;
  j["points"] = c.points;
  j["outside"] = c.outside;
  j["share_outside"] = c.share_outside;
  j["fits"] = c.fits;
  json runs = json::array();
  for (const TauRange& r : c.disagree) runs.push_back({r.lo_s, r.hi_s});
  j["disagree_tau_s"] = runs;
  j["from_tau_s"] = c.from_tau_s;
  j["excluded_points"] = c.excluded;
  return j;
}

json AxisJson(const AxisNoise& a, bool gyro) {
  json j;
  for (int t = 0; t < kNoiseTermCount; ++t) {
    j[NoiseTermKey(static_cast<NoiseTerm>(t), gyro)] = TermJson(a.terms[t]);
  }
  const std::string u = SensorUnitKey(gyro);
  // The terms real sensors add, each in the model only when the curve shows it.
  j["gauss_markov"] = GaussMarkovJson(a.gauss_markov, u);
  j["sinusoid"] = SinusoidJson(a.sinusoid, u);
  // The fitted model held against the curve (ModelCheck).
  j["model_check"] = CheckJson(a.check);
  const AllanPoint* min = a.curve.empty() ? nullptr : &a.curve.front();
  for (const AllanPoint& p : a.curve) {
    if (p.adev < min->adev) min = &p;
  }
  if (min) {
    j["adev_min_" + u] = min->adev;
    j["adev_min_tau_s"] = min->tau_s;
  }
  json allan;
  json tau = json::array(), adev = json::array(), lo = json::array(), hi = json::array(),
       edf = json::array(), m = json::array(), stride = json::array(),
       type = json::array();
  for (const AllanPoint& p : a.curve) {
    tau.push_back(p.tau_s);
    adev.push_back(p.adev);
    lo.push_back(p.adev_lo);
    hi.push_back(p.adev_hi);
    edf.push_back(p.edf);
    m.push_back(p.m);
    stride.push_back(p.stride);
    type.push_back(std::string(ToString(p.dominant)));
  }
  allan["tau_s"] = tau;
  allan["adev_" + u] = adev;
  allan["adev_lo_" + u] = lo;
  allan["adev_hi_" + u] = hi;
  allan["edf"] = edf;
  allan["m"] = m;
  allan["stride"] = stride;
  allan["noise_type"] = type;
  // The fitted model (every term, squared, in the variance domain), to draw
  // the fitted curve; values are reported only in the terms above.
  json fit;
  for (int t = 0; t < kNoiseTermCount; ++t) {
    fit[std::string(ToString(static_cast<NoiseTerm>(t)))] = a.fit_avar_coefficients[t];
  }
  allan["fit_avar_coefficients"] = fit;
  allan["fit_gauss_markov"] = {{"sigma_" + u, std::sqrt(a.fit_gauss_markov.sigma2)},
                               {"tau_c_s", a.fit_gauss_markov.tau_c_s}};
  allan["fit_sinusoid"] = {{"amplitude_" + u, std::sqrt(a.fit_sinusoid.amplitude2)},
                           {"period_s", a.fit_sinusoid.period_s}};
  j["allan"] = allan;
  return j;
}

json SensorJson(const SensorNoise& s, bool gyro) {
  json j;
  j[std::string("mean_") + SensorUnitKey(gyro)] = {
      s.mean_si.x(), s.mean_si.y(), s.mean_si.z()};
  json axes;
  for (int i = 0; i < 3; ++i) axes[kAxisNames[i]] = AxisJson(s.axes[i], gyro);
  j["axes"] = axes;
  // How long to record to measure each term not seen (SetRecordNeeded).
  json needed;
  for (int t = 0; t < kNoiseTermCount; ++t) {
    needed[std::string(ToString(static_cast<NoiseTerm>(t)))] =
        s.record_needed_s[t] ? json(*s.record_needed_s[t]) : json(nullptr);
  }
  j["record_needed_s"] = needed;
  return j;
}

std::optional<NoiseTerm> ParseTerm(std::string_view s) {
  for (int t = 0; t < kNoiseTermCount; ++t) {
    if (ToString(static_cast<NoiseTerm>(t)) == s) return static_cast<NoiseTerm>(t);
  }
  return std::nullopt;
}

TermEstimate ReadTerm(const JsonReader& r, const json& o, const std::string& path) {
  TermEstimate e;
  const std::string status = r.String(o, path, "status");
  if (status == "measured") {
    e.status = TermStatus::kMeasured;
    e.value = r.Number(o, path, "value");
    e.lo = r.Number(o, path, "lo");
    e.hi = r.Number(o, path, "hi");
    const json& range =
        r.ArrayValue(r.Field(o, path, "tau_range_s"), path + ".tau_range_s", 2);
    e.tau_lo_s = r.NumberValue(range[0], path + ".tau_range_s[0]");
    e.tau_hi_s = r.NumberValue(range[1], path + ".tau_range_s[1]");
  } else if (status == "not_seen" || status == "masked" || status == "disagrees") {
    e.status = status == "masked"      ? TermStatus::kMasked
               : status == "disagrees" ? TermStatus::kDisagrees
                                       : TermStatus::kNotSeen;
    e.upper_bound = r.Number(o, path, "upper_bound");
    const json& need = r.Field(o, path, "record_needed_s");
    if (!need.is_null())
      e.record_needed_s = r.NumberValue(need, path + ".record_needed_s");
  } else {
    r.Fail(
        fmt::format("field '{}.status' must be measured, not_seen, masked or disagrees, "
                    "found '{}'",
                    path,
                    status));
  }
  return e;
}

std::vector<double> Numbers(const JsonReader& r,
                            const json& o,
                            const std::string& path,
                            const std::string& key,
                            std::size_t size) {
  const std::string field = JsonReader::Join(path, key);
  const json& a = r.ArrayValue(r.Field(o, path, key), field, size);
  std::vector<double> v;
  for (std::size_t i = 0; i < a.size(); ++i) {
    v.push_back(r.NumberValue(a[i], fmt::format("{}[{}]", field, i)));
  }
  return v;
}

// The model check; a file without one (written before the check existed in
// this format) reads as not checked (points 0).
ModelCheck ReadCheck(const JsonReader& r, const json& o, const std::string& path) {
  ModelCheck c;
  if (!o.contains("model_check")) return c;
  const std::string cp = JsonReader::Join(path, "model_check");
  const json& j = r.Object(o, path, "model_check");
  c.points = static_cast<int>(r.Integer(j, cp, "points", 0, 1 << 20));
  c.outside = static_cast<int>(r.Integer(j, cp, "outside", 0, c.points));
  c.share_outside = r.Number(j, cp, "share_outside");
  c.fits = r.Bool(j, cp, "fits");
  c.from_tau_s = r.Number(j, cp, "from_tau_s");
  c.excluded = static_cast<int>(r.Integer(j, cp, "excluded_points", 0, 1 << 20));
  const std::string dp = cp + ".disagree_tau_s";
  const json& runs = r.Field(j, cp, "disagree_tau_s");
  if (!runs.is_array()) r.Fail(fmt::format("field '{}' must be an array", dp));
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const std::string ip = fmt::format("{}[{}]", dp, i);
    const json& run = r.ArrayValue(runs[i], ip, 2);
    c.disagree.push_back(
        TauRange{r.NumberValue(run[0], ip + "[0]"), r.NumberValue(run[1], ip + "[1]")});
  }
  return c;
}

// The status of an extra term and whether it was modelled; its figures are
// read by the caller when measured.
TermStatus ReadExtraStatus(const JsonReader& r,
                           const json& o,
                           const std::string& path,
                           bool& modelled) {
  const std::string status = r.String(o, path, "status");
  modelled = r.Bool(o, path, "modelled");
  if (status == "measured") return TermStatus::kMeasured;
  if (status == "not_seen") return TermStatus::kNotSeen;
  if (status == "disagrees") return TermStatus::kDisagrees;
  r.Fail(
      fmt::format("field '{}.status' must be measured, not_seen or disagrees, found '{}'",
                  path,
                  status));
  return TermStatus::kNotSeen;
}

void ReadRange(const JsonReader& r,
               const json& o,
               const std::string& path,
               double& lo_s,
               double& hi_s) {
  const json& range =
      r.ArrayValue(r.Field(o, path, "tau_range_s"), path + ".tau_range_s", 2);
  lo_s = r.NumberValue(range[0], path + ".tau_range_s[0]");
  hi_s = r.NumberValue(range[1], path + ".tau_range_s[1]");
}

// The Gauss-Markov process and the sinusoid of an axis; a file without them
// (written before they were modelled) reads as not seen.
void ReadExtraTerms(const JsonReader& r,
                    const json& o,
                    const std::string& path,
                    const std::string& u,
                    AxisNoise& a) {
  if (o.contains("gauss_markov")) {
    const std::string gp = JsonReader::Join(path, "gauss_markov");
    const json& j = r.Object(o, path, "gauss_markov");
    GaussMarkovTerm& g = a.gauss_markov;
    g.status = ReadExtraStatus(r, j, gp, g.modelled);
    if (g.status == TermStatus::kMeasured) {
      g.sigma = r.Number(j, gp, "sigma_" + u);
      g.sigma_lo = r.Number(j, gp, "sigma_lo_" + u);
      g.sigma_hi = r.Number(j, gp, "sigma_hi_" + u);
      g.tau_c_s = r.Number(j, gp, "tau_c_s");
      g.tau_c_lo_s = r.Number(j, gp, "tau_c_lo_s");
      g.tau_c_hi_s = r.Number(j, gp, "tau_c_hi_s");
      ReadRange(r, j, gp, g.tau_lo_s, g.tau_hi_s);
    }
  }
  if (o.contains("sinusoid")) {
    const std::string sp = JsonReader::Join(path, "sinusoid");
    const json& j = r.Object(o, path, "sinusoid");
    SinusoidTerm& s = a.sinusoid;
    s.status = ReadExtraStatus(r, j, sp, s.modelled);
    if (s.status == TermStatus::kMeasured) {
      s.amplitude = r.Number(j, sp, "amplitude_" + u);
      s.amplitude_lo = r.Number(j, sp, "amplitude_lo_" + u);
      s.amplitude_hi = r.Number(j, sp, "amplitude_hi_" + u);
      s.period_s = r.Number(j, sp, "period_s");
      s.period_lo_s = r.Number(j, sp, "period_lo_s");
      s.period_hi_s = r.Number(j, sp, "period_hi_s");
      ReadRange(r, j, sp, s.tau_lo_s, s.tau_hi_s);
    }
  }
}

AxisNoise ReadAxis(const JsonReader& r,
                   const json& o,
                   const std::string& path,
                   bool gyro) {
  AxisNoise a;
  for (int t = 0; t < kNoiseTermCount; ++t) {
    const std::string key = NoiseTermKey(static_cast<NoiseTerm>(t), gyro);
    a.terms[t] = ReadTerm(r, r.Object(o, path, key), JsonReader::Join(path, key));
  }
  a.check = ReadCheck(r, o, path);
  const std::string u = SensorUnitKey(gyro);
  ReadExtraTerms(r, o, path, u, a);
  const std::string ap = JsonReader::Join(path, "allan");
  const json& allan = r.Object(o, path, "allan");
  const json& tau_json = r.Field(allan, ap, "tau_s");
  if (!tau_json.is_array()) r.Fail(fmt::format("field '{}.tau_s' must be an array", ap));
  const std::size_t n = tau_json.size();
  const std::vector<double> tau = Numbers(r, allan, ap, "tau_s", n);
  const std::vector<double> adev = Numbers(r, allan, ap, "adev_" + u, n);
  const std::vector<double> lo = Numbers(r, allan, ap, "adev_lo_" + u, n);
  const std::vector<double> hi = Numbers(r, allan, ap, "adev_hi_" + u, n);
  const std::vector<double> edf = Numbers(r, allan, ap, "edf", n);
  const json& types =
      r.ArrayValue(r.Field(allan, ap, "noise_type"), ap + ".noise_type", n);
  for (std::size_t i = 0; i < n; ++i) {
    AllanPoint p;
    p.tau_s = tau[i];
    p.adev = adev[i];
    p.avar = adev[i] * adev[i];
    p.adev_lo = lo[i];
    p.adev_hi = hi[i];
    p.edf = edf[i];
    const auto term = types[i].is_string() ? ParseTerm(types[i].get<std::string>())
                                           : std::optional<NoiseTerm>();
    if (!term)
      r.Fail(fmt::format("field '{}.noise_type[{}]' is not a noise term", ap, i));
    p.dominant = *term;
    a.curve.push_back(p);
  }
  const std::string fp = ap + ".fit_avar_coefficients";
  const json& fit = r.Object(allan, ap, "fit_avar_coefficients");
  for (int t = 0; t < kNoiseTermCount; ++t) {
    a.fit_avar_coefficients[t] = r.Number(fit, fp, ToString(static_cast<NoiseTerm>(t)));
  }
  if (allan.contains("fit_gauss_markov")) {
    const std::string gp = ap + ".fit_gauss_markov";
    const json& g = r.Object(allan, ap, "fit_gauss_markov");
    const double sigma = r.Number(g, gp, "sigma_" + u);
    a.fit_gauss_markov.sigma2 = sigma * sigma;
    a.fit_gauss_markov.tau_c_s = r.Number(g, gp, "tau_c_s");
  }
  if (allan.contains("fit_sinusoid")) {
    const std::string sp = ap + ".fit_sinusoid";
    const json& sj = r.Object(allan, ap, "fit_sinusoid");
    const double amplitude = r.Number(sj, sp, "amplitude_" + u);
    a.fit_sinusoid.amplitude2 = amplitude * amplitude;
    a.fit_sinusoid.period_s = r.Number(sj, sp, "period_s");
  }
  return a;
}

SensorNoise ReadSensor(const JsonReader& r,
                       const json& o,
                       const std::string& path,
                       bool gyro) {
  SensorNoise s;
  s.mean_si = r.Vector(o, path, std::string("mean_") + SensorUnitKey(gyro));
  const std::string axes_path = JsonReader::Join(path, "axes");
  const json& axes = r.Object(o, path, "axes");
  for (int i = 0; i < 3; ++i) {
    s.axes[i] = ReadAxis(r,
                         r.Object(axes, axes_path, kAxisNames[i]),
                         JsonReader::Join(axes_path, kAxisNames[i]),
                         gyro);
  }
  SetRecordNeeded(s);
  return s;
}

}  // namespace

std::string NoiseTermKey(NoiseTerm term, bool gyro) {
  switch (term) {
    case NoiseTerm::kQuantisation:
      return gyro ? "quantisation_rad" : "quantisation_mps";
    case NoiseTerm::kWhiteNoise:
      return gyro ? "white_noise_radps_per_rthz" : "white_noise_mps2_per_rthz";
    case NoiseTerm::kBiasInstability:
      return gyro ? "bias_instability_radps" : "bias_instability_mps2";
    case NoiseTerm::kRandomWalk:
      return gyro ? "random_walk_radps2_per_rthz" : "random_walk_mps3_per_rthz";
    case NoiseTerm::kRateRamp:
      return gyro ? "rate_ramp_radps2" : "rate_ramp_mps3";
  }
  return "?";
}

std::string NoiseJson(const NoiseResult& r, const std::string& input, double confidence) {
  json j;
  j["format"] = kFormat;
  j["input"] = input;
  j["segment"] = {{"kind", std::string(ToString(r.segment.kind))},
                  {"begin", r.segment.begin},
                  {"end", r.segment.end},
                  {"static_intervals", r.segment.static_intervals}};
  j["rate_hz"] = r.rate_hz;
  j["sample_period_s"] = r.sample_period_s;
  j["record_s"] = r.record_s;
  j["samples"] = r.samples;
  j["gaps"] = r.gaps;
  j["confidence"] = confidence;
  j["accelerometer"] = SensorJson(r.accel_mps2, false);
  if (r.gyro_radps) j["gyroscope"] = SensorJson(*r.gyro_radps, true);
  return FiniteJsonText(j, 1, "the noise analysis");
}

NoiseFile ParseNoiseJson(const std::string& text, const std::string& origin) {
  const JsonReader r(origin, Stage::kNoise);
  const json doc = r.Parse(text);
  r.ExpectFormat(doc, "mpcal.noise", 1);
  NoiseFile f;
  f.input = r.String(doc, "", "input");
  f.confidence = r.Number(doc, "", "confidence");
  NoiseResult& res = f.result;
  res.rate_hz = r.Number(doc, "", "rate_hz");
  res.sample_period_s = r.Number(doc, "", "sample_period_s");
  res.record_s = r.Number(doc, "", "record_s");
  res.samples = static_cast<std::size_t>(r.Integer(doc, "", "samples", 0, 1LL << 50));
  res.gaps = static_cast<std::size_t>(r.Integer(doc, "", "gaps", 0, 1LL << 50));
  const json& seg = r.Object(doc, "", "segment");
  res.segment.kind = r.String(seg, "segment", "kind") == "longest_still"
                         ? NoiseSegmentKind::kLongestStill
                         : NoiseSegmentKind::kWholeRecord;
  res.segment.begin =
      static_cast<std::size_t>(r.Integer(seg, "segment", "begin", 0, 1LL << 50));
  res.segment.end =
      static_cast<std::size_t>(r.Integer(seg, "segment", "end", 0, 1LL << 50));
  res.accel_mps2 =
      ReadSensor(r, r.Object(doc, "", "accelerometer"), "accelerometer", false);
  if (doc.contains("gyroscope")) {
    res.gyro_radps = ReadSensor(r, r.Object(doc, "", "gyroscope"), "gyroscope", true);
  }
  return f;
}

NoiseFile ReadNoiseFile(const std::string& path) {
  const std::string origin = fmt::format("noise file '{}'", path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(origin + ": cannot be opened (does it exist?)");
  std::ostringstream text;
  text << in.rdbuf();
  return ParseNoiseJson(text.str(), origin);
}

}  // namespace mpcal
