// The noise section: each axis's Allan deviation on log-log axes with its
// confidence band, the fitted terms and their sum, and the terms table in SI
// and datasheet units.
#include <cmath>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "mpcal/noise_units.h"
#include "report/html.h"
#include "report/line_plot.h"
#include "report/sections.h"

namespace mpcal::report {
namespace {

constexpr const char* kAxis[3] = {"x", "y", "z"};

const char* TermName(NoiseTerm t) {
  switch (t) {
    case NoiseTerm::kQuantisation:
      return "quantisation Q";
    case NoiseTerm::kWhiteNoise:
      return "white noise N";
    case NoiseTerm::kBiasInstability:
      return "bias instability B";
    case NoiseTerm::kRandomWalk:
      return "random walk K";
    case NoiseTerm::kRateRamp:
      return "rate ramp R";
  }
  return "";
}

// σ(τ) of one term alone (IEEE 952 Table C.2).
double TermAdev(NoiseTerm t, double v, double tau_s) {
  switch (t) {
    case NoiseTerm::kQuantisation:
      return std::sqrt(3.0) * v / tau_s;
    case NoiseTerm::kWhiteNoise:
      return v / std::sqrt(tau_s);
    case NoiseTerm::kBiasInstability:
      return v * std::sqrt(2.0 * std::log(2.0) / M_PI);
    case NoiseTerm::kRandomWalk:
      return v * std::sqrt(tau_s / 3.0);
    case NoiseTerm::kRateRamp:
      return v * tau_s / std::sqrt(2.0);
  }
  return 0.0;
}

// `needed_s`: the sensor's one record length for the term (SensorNoise::
// record_needed_s), the figure every output gives.
std::string Cell(const TermEstimate& e, double factor, std::optional<double> needed_s) {
  if (e.value) {
    return fmt::format("{} [{}, {}]",
                       Significant(*e.value * factor, 4),
                       Significant(e.lo * factor, 3),
                       Significant(e.hi * factor, 3));
  }
  if (e.upper_bound > 0.0) {
    std::string s =
        fmt::format("not measured: < {}", Significant(e.upper_bound * factor, 3));
    if (e.status == TermStatus::kMasked) s += " (below its neighbours)";
    if (e.status == TermStatus::kDisagrees) s += " (the model misses the curve there)";
    if (e.record_needed_s && needed_s)
      s += fmt::format("; record \u2265 {}", FormatRecordLength(*needed_s));
    return s;
  }
  return "not measured";
}

std::string TermsTable(const SensorNoise& s, bool gyro) {
  Table t("noise-terms");
  t.Header({gyro ? "gyroscope" : "accelerometer", "unit", "x", "y", "z"});
  for (int i = 0; i < kNoiseTermCount; ++i) {
    const NoiseTerm term = static_cast<NoiseTerm>(i);
    bool any = false;
    for (const AxisNoise& a : s.axes) any = any || a.term(term).value.has_value();
    if (!any && (term == NoiseTerm::kQuantisation || term == NoiseTerm::kRateRamp))
      continue;
    std::vector<std::string> si = {TermName(term), noise_units::SiUnit(term, gyro)};
    for (const AxisNoise& a : s.axes)
      si.push_back(Cell(a.term(term), 1.0, s.record_needed_s[i]));
    t.Row(si);
    const noise_units::DatasheetValue unit = noise_units::ToDatasheet(term, gyro, 1.0);
    if (unit.unit[0] == '\0') continue;
    std::vector<std::string> ds = {"", unit.unit};
    for (const AxisNoise& a : s.axes)
      ds.push_back(Cell(a.term(term), unit.value, s.record_needed_s[i]));
    t.Row(ds);
  }
  std::vector<std::string> check = {"model vs curve", "cluster times"};
  for (const AxisNoise& a : s.axes) {
    const ModelCheck& c = a.check;
    if (c.points == 0) {
      check.emplace_back("not checked");
      continue;
    }
    std::string cell = fmt::format(
        "{}: {} of {} outside", c.fits ? "fits" : "misses", c.outside, c.points);
    if (!c.fits) cell += " at " + FormatTauRanges(c.disagree, 3);
    if (c.excluded > 0)
      cell += fmt::format("; fitted from \u03c4 = {:.3g} s", c.from_tau_s);
    check.push_back(cell);
  }
  t.Row(check);
  return t.Finish();
}

// A term's own line, dashed, over the cluster times [lo_s, hi_s] it was
// read from, not beyond: where the curve supports it. `adev` gives its σ(τ),
// or nothing where it has no point.
template <typename Adev>
Series TermLine(std::string label,
                int style,
                const std::vector<AllanPoint>& curve,
                TauRange read_over,
                Adev adev) {
  Series line{std::move(label), {}, {}, StandardStyle(style), true, false};
  line.style.dash = "5,4";
  for (const AllanPoint& p : curve) {
    if (p.tau_s < read_over.lo_s || p.tau_s > read_over.hi_s) continue;
    const std::optional<double> y = adev(p.tau_s);
    if (!y) continue;
    line.x.push_back(p.tau_s);
    line.y.push_back(*y);
  }
  return line;
}

// Each measured term's line (slope −1, −½, 0, +½, +1), then the Gauss-Markov
// bump's and the sinusoid's, each in the next style from `style` on.
void AddTermLines(const AxisNoise& a, int style, LinePlotSpec& spec) {
  for (int i = 0; i < kNoiseTermCount; ++i) {
    const TermEstimate& e = a.terms[i];
    if (!e.value) continue;
    const auto term = static_cast<NoiseTerm>(i);
    const TauRange read_over{e.tau_lo_s, e.tau_hi_s};
    spec.series.push_back(TermLine(
        fmt::format("{} = {}, read over τ {}",
                    TermName(term),
                    Significant(*e.value, 3),
                    FormatTauRanges({read_over}, 1)),
        style++,
        a.curve,
        read_over,
        [&](double tau_s) { return std::optional(TermAdev(term, *e.value, tau_s)); }));
  }
  if (const GaussMarkovTerm& g = a.gauss_markov; g.sigma) {
    const TauRange read_over{g.tau_lo_s, g.tau_hi_s};
    const double sigma2 = *g.sigma * *g.sigma;
    spec.series.push_back(TermLine(
        fmt::format("Gauss-Markov σ = {}, τc = {} s, read over τ {}",
                    Significant(*g.sigma, 3),
                    Significant(g.tau_c_s, 3),
                    FormatTauRanges({read_over}, 1)),
        style++,
        a.curve,
        read_over,
        [&](double tau_s) {
          return std::optional(std::sqrt(GaussMarkovAvar(sigma2, g.tau_c_s, tau_s)));
        }));
  }
  if (const SinusoidTerm& w = a.sinusoid; w.amplitude) {
    const TauRange read_over{w.tau_lo_s, w.tau_hi_s};
    const double amplitude2 = *w.amplitude * *w.amplitude;
    spec.series.push_back(
        TermLine(fmt::format("sinusoid A = {}, P = {} s, read over τ {}",
                             Significant(*w.amplitude, 3),
                             Significant(w.period_s, 3),
                             FormatTauRanges({read_over}, 1)),
                 style,
                 a.curve,
                 read_over,
                 [&](double tau_s) -> std::optional<double> {
                   const double v = SinusoidAvar(amplitude2, w.period_s, tau_s);
                   // Its zeros at whole periods: off the log axis.
                   if (!(v > 0.0)) return std::nullopt;
                   return std::sqrt(v);
                 }));
  }
}

// Where the fitted model lies outside the curve's interval (ModelCheck),
// shaded: no term is read there.
void AddMisfitBands(const ModelCheck& check, LinePlotSpec& spec) {
  for (const TauRange& r : check.disagree) {
    spec.bands.push_back({r.lo_s, r.hi_s, "", "band-misfit"});
  }
  if (check.disagree.empty()) return;
  spec.extra_legend.push_back({"the model misses the curve (outside its interval)",
                               {},
                               true,
                               "band-misfit",
                               false});
}

// The sum of the fitted terms over the cluster times fitted (from
// ModelCheck::from_tau_s).
Series FittedSum(const AxisNoise& a) {
  Series sum{"sum of the fitted terms", {}, {}, StandardStyle(1), true, false};
  for (const AllanPoint& p : a.curve) {
    if (p.tau_s < a.check.from_tau_s) continue;
    sum.x.push_back(p.tau_s);
    sum.y.push_back(std::sqrt(a.FittedAvar(p.tau_s)));
  }
  return sum;
}

std::string AllanPlot(const AxisNoise& a, bool gyro, int axis) {
  LinePlotSpec spec;
  spec.log_x = true;
  spec.log_y = true;
  const std::string unit = gyro ? "rad/s" : "m/s\u00b2";
  spec.aria_label = fmt::format("Allan deviation of the {} {} axis",
                                gyro ? "gyroscope" : "accelerometer",
                                kAxis[axis]);
  spec.axes = {"cluster time \u03c4 (s)", fmt::format("Allan deviation ({})", unit)};
  FillBetween band;
  Series adev{"Allan deviation", {}, {}, StandardStyle(0), true, true};
  adev.style.marker = MarkerShape::kCircle;
  for (const AllanPoint& p : a.curve) {
    band.x.push_back(p.tau_s);
    band.lo.push_back(p.adev_lo);
    band.hi.push_back(p.adev_hi);
    adev.x.push_back(p.tau_s);
    adev.y.push_back(p.adev);
  }
  spec.fills.push_back(band);
  spec.series.push_back(adev);
  if (a.curve.empty()) return LinePlot(spec);
  AddMisfitBands(a.check, spec);
  AddTermLines(a, 2, spec);
  spec.series.push_back(FittedSum(a));
  spec.y_include = Interval{a.curve.front().adev_lo, a.curve.front().adev_hi};
  return LinePlot(spec);
}

}  // namespace

std::string NoiseSection(const NoiseFile& f) {
  const NoiseResult& r = f.result;
  std::string html = "<section id=\"noise\">\n<h2>Noise</h2>\n";
  html += Paragraph(fmt::format(
      "{}: {:.2f} h at {:.6g} Hz, {} samples ({}). Overlapping Allan deviation with its "
      "{:.0f} % "
      "confidence band (equivalent degrees of freedom of the overlapping estimator for "
      "the noise "
      "type that dominates at each \u03c4); the terms fitted in the variance domain, "
      "each only where "
      "it dominates the curve. Densities are continuous-time: per sample \u03c3 = "
      "N\u00b7\u221arate.",
      f.input,
      r.record_s / 3600.0,
      r.rate_hz,
      r.samples,
      r.segment.kind == NoiseSegmentKind::kWholeRecord ? "the whole record"
                                                       : "the longest still part",
      100.0 * f.confidence));
  for (const bool gyro : {false, true}) {
    const SensorNoise* s =
        gyro ? (r.gyro_radps ? &*r.gyro_radps : nullptr) : &r.accel_mps2;
    if (!s) continue;
    html += fmt::format("<h3>{}</h3>\n", gyro ? "Gyroscope" : "Accelerometer");
    html += TermsTable(*s, gyro);
    for (int axis = 0; axis < 3; ++axis) {
      html += Figure(
          AllanPlot(s->axes[axis], gyro, axis),
          fmt::format("Allan deviation of the {} {} axis, its confidence band, each "
                      "measured term's line (dashed) over the cluster times it was read "
                      "from, their sum, and shaded where the model misses the curve.",
                      gyro ? "gyroscope" : "accelerometer",
                      kAxis[axis]));
    }
  }
  return html + "</section>\n";
}

}  // namespace mpcal::report
