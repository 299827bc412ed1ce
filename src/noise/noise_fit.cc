// The noise terms of one axis from its Allan curve: a non-negative weighted
// least-squares fit of the sum of the IEEE 952 terms in the variance domain,
// each term kept only where it dominates, with the confidence intervals of
// every point set from the noise type the fit says dominates there.
#include "noise/noise_fit.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "mpcal/error.h"
#include "mpcal/noise.h"

namespace mpcal {
namespace {

constexpr int kTerms = kNoiseTermCount;  // the IEEE five
// The columns beyond them: the Gauss-Markov process (σ²) and the sinusoid
// (A²), each linear in its coefficient for a given τc or P.
constexpr int kGaussMarkov = kTerms;
constexpr int kSinusoid = kTerms + 1;
constexpr int kColumns = kTerms + 2;
using TermMask = unsigned;
using Coefficients = std::array<double, kColumns>;  // Q², N², B², K², R², σ², A²
constexpr int kRampIndex = static_cast<int>(NoiseTerm::kRateRamp);
constexpr int kQuantIndex = static_cast<int>(NoiseTerm::kQuantisation);
constexpr TermMask kIeeeTerms = (1u << kTerms) - 1;

// σ²(τ) per unit coefficient of each term (IEEE 952 Table C.2).
double Basis(int term, double tau_s) {
  switch (static_cast<NoiseTerm>(term)) {
    case NoiseTerm::kQuantisation:
      return 3.0 / (tau_s * tau_s);
    case NoiseTerm::kWhiteNoise:
      return 1.0 / tau_s;
    case NoiseTerm::kBiasInstability:
      return 2.0 * std::numbers::ln2 / std::numbers::pi;
    case NoiseTerm::kRandomWalk:
      return tau_s / 3.0;
    case NoiseTerm::kRateRamp:
      return 0.5 * tau_s * tau_s;
  }
  return 0.0;
}

// σ²(τ) per unit N² of white noise through the first-order low-pass
// y_n = φ y_{n−1} + (1 − φ) x_n sampled every τ0 (unit gain at zero
// frequency): the output is an AR(1) sequence, and the variance of a sum of
// m of its samples gives, exactly at τ = m τ0,
//   σ²(τ) = (1/τ) [1 − φ/(1 − φ²) · (4(1 − φ^m) − (1 − φ^{2m})) / m],
// (1 − φ)²/((1 + φ) τ0) at m = 1, → 1/τ − 3φ τ0/((1 − φ²) τ²) for large m.
double FilteredWhite(double phi, double tau0_s, double tau_s) {
  const double m = std::max(1.0, std::round(tau_s / tau0_s));
  const double pm = std::pow(phi, m);
  const double r = phi / (1.0 - phi * phi);
  return (1.0 - r * (4.0 * (1.0 - pm) - (1.0 - pm * pm)) / m) / tau_s;
}

// The fitted model: the coefficients of every column, the correlation time
// and period that make the last two linear, and the low-pass filter the
// white noise went through (φ = 0: none).
struct Model {
  Coefficients c{};
  double tau_c_s = 1.0;
  double period_s = 1.0;
  double lowpass_phi = 0.0;
  double tau0_s = 0.0;

  double Column(int col, double tau_s) const {
    if (col == kGaussMarkov) return GaussMarkovAvar(1.0, tau_c_s, tau_s);
    if (col == kSinusoid) return SinusoidAvar(1.0, period_s, tau_s);
    if (col == static_cast<int>(NoiseTerm::kWhiteNoise) && lowpass_phi > 0.0)
      return FilteredWhite(lowpass_phi, tau0_s, tau_s);
    return Basis(col, tau_s);
  }
  double Part(int col, double tau_s) const { return c[col] * Column(col, tau_s); }
  double Avar(double tau_s) const {
    double sum = 0.0;
    for (int t = 0; t < kColumns; ++t) sum += Part(t, tau_s);
    return sum;
  }
};

// The IEEE terms a model fits: all five, or with the low-pass filter in
// the white noise's column all but the quantisation, whose 1/τ² at the
// short end trades against φ and N (a record quantised after its filter is
// left to the fit with the signed remnant, see AnalyseAxis).
TermMask IeeeTerms(const Model& m) {
  return m.lowpass_phi > 0.0 ? kIeeeTerms & ~(1u << kQuantIndex) : kIeeeTerms;
}

struct Fit {
  Model m;
  Coefficients variance{};  // of each coefficient
  double cost = std::numeric_limits<double>::infinity();
};

// Non-negative least squares over the columns in `allowed` that include
// all of `required`: the optimum lies on some support set where the
// unconstrained optimum is positive, so every such subset is tried (exact,
// and at most 127 tiny solves). `signed_terms`: those that may come out
// negative (the roll-off of a low-pass filter beyond its short-τ end, see
// AnalyseAxis). The model's τc and period are kept; its coefficients set.
Fit FitNonNegative(const std::vector<AllanPoint>& curve,
                   const std::vector<double>& weight,
                   const Model& shape,
                   TermMask allowed,
                   TermMask signed_terms = 0,
                   TermMask required = 0) {
  Fit best;
  best.m = shape;
  best.m.c = {};
  const int rows = static_cast<int>(curve.size());
  // The columns at every point, weighted, once.
  Eigen::MatrixXd full(rows, kColumns);
  Eigen::VectorXd b(rows);
  for (int j = 0; j < rows; ++j) {
    const double sw = std::sqrt(weight[j]);
    for (int t = 0; t < kColumns; ++t) {
      full(j, t) = (allowed & (1u << t)) ? sw * shape.Column(t, curve[j].tau_s) : 0.0;
    }
    b(j) = sw * curve[j].avar;
  }
  for (TermMask set = allowed; set != 0; set = (set - 1) & allowed) {
    if ((set & required) != required) continue;
    std::vector<int> cols;
    for (int t = 0; t < kColumns; ++t) {
      if (set & (1u << t)) cols.push_back(t);
    }
    const int k = static_cast<int>(cols.size());
    if (k > rows) continue;
    Eigen::MatrixXd a(rows, k);
    for (int i = 0; i < k; ++i) a.col(i) = full.col(cols[i]);
    // Columns scaled to unit norm: the terms differ by many decades.
    const Eigen::VectorXd scale = a.colwise().norm().transpose();
    if ((scale.array() <= 0.0).any()) continue;
    const Eigen::MatrixXd as = a * scale.cwiseInverse().asDiagonal();
    const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(as);
    if (qr.rank() < k) continue;
    const Eigen::VectorXd xs = qr.solve(b);
    const Eigen::VectorXd x = xs.cwiseQuotient(scale);
    bool negative = false;
    for (int i = 0; i < k; ++i) {
      negative = negative || (x(i) <= 0.0 && (signed_terms & (1u << cols[i])) == 0);
    }
    if (negative) continue;
    const Eigen::VectorXd fitted = a * x;
    if ((fitted.array() <= 0.0).any()) continue;
    const double cost = (fitted - b).squaredNorm();
    if (cost >= best.cost) continue;
    best.cost = cost;
    best.m.c = {};
    best.variance = {};
    const Eigen::MatrixXd cov_s = (as.transpose() * as).inverse();
    for (int i = 0; i < k; ++i) {
      best.m.c[cols[i]] = x(i);
      best.variance[cols[i]] = cov_s(i, i) / (scale(i) * scale(i));
    }
  }
  return best;
}

// The noise type of the EDF at τ: that of the largest part of the model. A
// Gauss-Markov process is a random walk below its correlation time and a
// white noise above; a sinusoid is taken as white.
NoiseTerm Dominant(const Model& m, double tau_s) {
  int arg = static_cast<int>(NoiseTerm::kWhiteNoise);
  double largest = -1.0;
  for (int t = 0; t < kColumns; ++t) {
    const double v = m.Part(t, tau_s);
    if (v > largest) largest = v, arg = t;
  }
  if (arg == kGaussMarkov)
    return tau_s < m.tau_c_s ? NoiseTerm::kRandomWalk : NoiseTerm::kWhiteNoise;
  if (arg == kSinusoid) return NoiseTerm::kWhiteNoise;
  return static_cast<NoiseTerm>(arg);
}

// EDF and interval of every point for the dominant term of `m` (white noise
// before any fit).
void SetIntervals(std::vector<AllanPoint>& curve,
                  const Model* m,
                  double phase_points,
                  double confidence) {
  const double lo_p = 0.5 * (1.0 - confidence);
  for (AllanPoint& p : curve) {
    p.dominant = m ? Dominant(*m, p.tau_s) : NoiseTerm::kWhiteNoise;
    p.edf =
        std::min(OverlappingAllanEdf(phase_points, static_cast<double>(p.m), p.dominant),
                 static_cast<double>(p.terms));
    p.adev_lo = std::sqrt(p.avar * p.edf / ChiSquareQuantile(1.0 - lo_p, p.edf));
    p.adev_hi = std::sqrt(p.avar * p.edf / ChiSquareQuantile(lo_p, p.edf));
  }
}

// Weights 1 / var(σ̂²) = edf / (2 model²), from the model's variance rather
// than the data's (weights from the data would pull the fit towards the
// points that came out low), with the curve's EDF as SetIntervals left it.
std::vector<double> ModelWeights(const std::vector<AllanPoint>& curve, const Model& m) {
  std::vector<double> weight(curve.size());
  for (std::size_t j = 0; j < curve.size(); ++j) {
    const double model = m.Avar(curve[j].tau_s);
    weight[j] = curve[j].edf / (2.0 * model * model);
  }
  return weight;
}

// The reweighted fit over the columns `allowed` (those in `required`
// always), at the τc and period of `shape`; weights from `start` when given
// (else from the data, then from the model).
Fit FitTerms(std::vector<AllanPoint>& curve,
             TermMask allowed,
             double phase_points,
             const NoiseOptions& o,
             TermMask signed_terms = 0,
             const Model& shape = Model{},
             TermMask required = 0,
             const Model* start = nullptr) {
  const double inflation = o.allan.points_per_octave / o.independent_points_per_octave;
  std::vector<double> weight(curve.size());
  if (start) {
    SetIntervals(curve, start, phase_points, o.allan.confidence);
    weight = ModelWeights(curve, *start);
  } else {
    SetIntervals(curve, nullptr, phase_points, o.allan.confidence);
    for (std::size_t j = 0; j < curve.size(); ++j) {
      weight[j] = curve[j].edf / (2.0 * curve[j].avar * curve[j].avar);
    }
  }
  Fit fit = FitNonNegative(curve, weight, shape, allowed, signed_terms, required);
  for (int it = 0; it < o.fit_iterations && std::isfinite(fit.cost); ++it) {
    SetIntervals(curve, &fit.m, phase_points, o.allan.confidence);
    const Fit next = FitNonNegative(
        curve, ModelWeights(curve, fit.m), shape, allowed, signed_terms, required);
    if (!std::isfinite(next.cost)) break;
    fit = next;
  }
  if (std::isfinite(fit.cost))
    SetIntervals(curve, &fit.m, phase_points, o.allan.confidence);
  for (double& v : fit.variance) v *= inflation;
  return fit;
}

// Points where column t carries at least `dominance` of the fitted variance.
std::vector<std::size_t> DominatedPoints(const std::vector<AllanPoint>& curve,
                                         const Model& m,
                                         int t,
                                         double dominance) {
  std::vector<std::size_t> out;
  for (std::size_t j = 0; j < curve.size(); ++j) {
    const double total = m.Avar(curve[j].tau_s);
    if (m.c[t] > 0.0 && m.Part(t, curve[j].tau_s) >= dominance * total) out.push_back(j);
  }
  return out;
}

// What the fit would give on a record of `record_s` whose curve is the model
// `m` (exactly): how many cluster times term t carries `dominance` of the
// variance at, and the variance of its coefficient, from the same weighted
// least squares (weights edf / (2 model²), over the terms of `m` with t,
// inflated for correlated τ) that FitTerms runs on a measured curve.
struct Forecast {
  int region_points = 0;
  double variance = std::numeric_limits<double>::infinity();
};

Forecast ForecastFit(
    const Model& m, int t, double record_s, const NoiseOptions& o, double tau0_s) {
  const auto samples = static_cast<std::int64_t>(record_s / tau0_s);
  const std::vector<std::int64_t> ms = internal::ClusterSizes(samples, o.allan);
  const double n = static_cast<double>(samples + 1);
  std::vector<int> cols;
  for (int j = 0; j < kColumns; ++j) {
    if (m.c[j] > 0.0) cols.push_back(j);
  }
  const auto k = static_cast<Eigen::Index>(cols.size());
  Eigen::MatrixXd a(static_cast<Eigen::Index>(ms.size()), k);
  Forecast f;
  for (std::size_t r = 0; r < ms.size(); ++r) {
    const double tau = static_cast<double>(ms[r]) * tau0_s;
    const double model = m.Avar(tau);
    const double edf =
        OverlappingAllanEdf(n, static_cast<double>(ms[r]), Dominant(m, tau));
    const double sw = std::sqrt(edf / 2.0) / model;
    for (Eigen::Index i = 0; i < k; ++i) {
      a(static_cast<Eigen::Index>(r), i) = sw * m.Column(cols[i], tau);
    }
    f.region_points += m.Part(t, tau) >= o.dominance * model;
  }
  const Eigen::VectorXd scale = a.colwise().norm().transpose();
  if (a.rows() < k || (scale.array() <= 0.0).any()) return f;
  const Eigen::MatrixXd as = a * scale.cwiseInverse().asDiagonal();
  const Eigen::MatrixXd normal = as.transpose() * as;
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(normal);
  if (ldlt.info() != Eigen::Success) return f;
  const Eigen::MatrixXd cov = ldlt.solve(Eigen::MatrixXd::Identity(k, k));
  const auto it = std::find(cols.begin(), cols.end(), t);
  const auto i = static_cast<Eigen::Index>(it - cols.begin());
  f.variance = cov(i, i) / (scale(i) * scale(i)) * o.allan.points_per_octave /
               o.independent_points_per_octave;
  return f;
}

// The shortest record, longer than `record_s`, in which term t at
// coefficient c_t, with the other fitted terms as they are, would be
// reported as measured in 9 records of 10: it carries `dominance` of the
// variance at min_region_points cluster times and its coefficient is above
// zero by the interval with 90 % power (c_t > (z + 1.28)·σ, σ as the fit
// would find it on that record). Records grow by an eighth of an octave up to 10⁹ s;
// NaN when none (the neighbouring terms hide it at every length).
double RecordNeeded(
    Model m, int t, double c_t, double record_s, double tau0_s, const NoiseOptions& o) {
  m.c[t] = c_t;
  // Above zero by the interval (z) in 9 records of 10: z + the 90 % normal
  // quantile standard deviations of the coefficient.
  constexpr double kPowerQuantile = 1.2815515655446004;
  const double z = std::sqrt(ChiSquareQuantile(o.allan.confidence, 1.0)) + kPowerQuantile;
  for (double length = record_s * std::exp2(0.125); length < 1e9;
       length *= std::exp2(0.125)) {
    const Forecast f = ForecastFit(m, t, length, o, tau0_s);
    if (f.region_points >= o.min_region_points && c_t > z * std::sqrt(f.variance))
      return length;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

// A coefficient's value and interval from its variance, as a scaled χ² with
// ν = 2 c² / var(c) degrees of freedom (exact for one point; keeps the
// interval positive): √c and the limits of √c.
struct RootInterval {
  double value = 0.0;
  double lo = 0.0;
  double hi = 0.0;
};

RootInterval CoefficientInterval(double c, double variance, double confidence) {
  const double lo_p = 0.5 * (1.0 - confidence);
  const double nu = std::max(2.0 * c * c / variance, 0.1);
  return {std::sqrt(c),
          std::sqrt(c * nu / ChiSquareQuantile(1.0 - lo_p, nu)),
          std::sqrt(c * nu / ChiSquareQuantile(lo_p, nu))};
}

// Measured terms: value and interval from the coefficient's variance.
void MeasureTerms(const std::vector<AllanPoint>& curve,
                  const Fit& fit,
                  const NoiseOptions& o,
                  AxisNoise& out) {
  const double z = std::sqrt(ChiSquareQuantile(o.allan.confidence, 1.0));
  for (int t = 0; t < kTerms; ++t) {
    const std::vector<std::size_t> region = DominatedPoints(curve, fit.m, t, o.dominance);
    const double c = fit.m.c[t];
    const bool significant = c > z * std::sqrt(fit.variance[t]);
    if (static_cast<int>(region.size()) < o.min_region_points || !significant) continue;
    TermEstimate& e = out.terms[t];
    const RootInterval v = CoefficientInterval(c, fit.variance[t], o.allan.confidence);
    e.status = TermStatus::kMeasured;
    e.value = v.value;
    e.lo = v.lo;
    e.hi = v.hi;
    e.tau_lo_s = curve[region.front()].tau_s;
    e.tau_hi_s = curve[region.back()].tau_s;
  }
}

// The terms not measured: the tightest upper confidence limit of the term
// alone, and for bias instability and random walk whether a longer record
// would show them at that bound and how long (RecordNeeded).
void BoundTerms(const std::vector<AllanPoint>& curve,
                const Fit& fit,
                double record_s,
                const NoiseOptions& o,
                AxisNoise& out) {
  const double tau0_s = curve.front().tau_s / static_cast<double>(curve.front().m);
  const bool walk_measured = out.term(NoiseTerm::kRandomWalk).value.has_value() ||
                             out.term(NoiseTerm::kRateRamp).value.has_value();
  // The forecast's other terms: as fitted, but a rate ramp only where it was
  // measured (an insignificant one, extrapolated as τ², would hide
  // everything at long τ).
  Model others = fit.m;
  if (!out.term(NoiseTerm::kRateRamp).value) others.c[kRampIndex] = 0.0;
  for (int t = 0; t < kTerms; ++t) {
    TermEstimate& e = out.terms[t];
    if (e.status == TermStatus::kMeasured) continue;
    double bound = std::numeric_limits<double>::infinity();
    for (const AllanPoint& p : curve) {
      bound = std::min(bound, std::sqrt(p.adev_hi * p.adev_hi / Basis(t, p.tau_s)));
    }
    e.upper_bound = std::isfinite(bound) ? bound : 0.0;
    // A longer record does not mend a model that misses an effect.
    if (e.status == TermStatus::kDisagrees) continue;
    const auto term = static_cast<NoiseTerm>(t);
    if (term == NoiseTerm::kBiasInstability && walk_measured) {
      // The random walk rises before the white noise falls to this level:
      // a flat region that is not there in this record never will be.
      e.status = TermStatus::kMasked;
      continue;
    }
    if (term != NoiseTerm::kBiasInstability && term != NoiseTerm::kRandomWalk) continue;
    if (e.upper_bound <= 0.0) continue;
    const double needed =
        RecordNeeded(others, t, e.upper_bound * e.upper_bound, record_s, tau0_s, o);
    if (std::isfinite(needed)) {
      e.record_needed_s = needed;
      const double half = RecordNeeded(
          others, t, 0.25 * e.upper_bound * e.upper_bound, record_s, tau0_s, o);
      if (std::isfinite(half)) e.record_needed_half_s = half;
    } else {
      e.status = TermStatus::kMasked;
    }
  }
}

// The fitted model `m` against the curve: the cluster times where its σ(τ)
// lies outside the curve's interval, and their runs.
ModelCheck CheckModel(const std::vector<AllanPoint>& curve,
                      const Model& m,
                      const NoiseOptions& o) {
  ModelCheck check;
  check.points = static_cast<int>(curve.size());
  if (curve.empty()) return check;
  check.from_tau_s = curve.front().tau_s;
  bool in_run = false;
  for (const AllanPoint& p : curve) {
    const double fitted = std::sqrt(m.Avar(p.tau_s));
    const bool outside = !(fitted >= p.adev_lo && fitted <= p.adev_hi);
    if (outside) {
      ++check.outside;
      if (!in_run) check.disagree.push_back(TauRange{p.tau_s, p.tau_s});
      check.disagree.back().hi_s = p.tau_s;
    }
    in_run = outside;
  }
  check.share_outside =
      static_cast<double>(check.outside) / static_cast<double>(check.points);
  check.fits = check.share_outside <= o.max_misfit_share;
  return check;
}

// Where the Allan deviation of each extra term peaks, per unit of its τc or
// P: a Gauss-Markov bump at 1.89 τc (the maximum of GaussMarkovAvar), a
// sinusoid at 0.371 P (tan x = 2x at x = πτ/P).
constexpr double kGaussMarkovPeak = 1.8926;
constexpr double kSinusoidPeak = 0.37103;

double& ShapeOf(Model& m, int col) {
  return col == kGaussMarkov ? m.tau_c_s : m.period_s;
}
double ShapeOf(const Model& m, int col) {
  return col == kGaussMarkov ? m.tau_c_s : m.period_s;
}

// Pearson's statistic of the model against the curve, Σ edf (σ̂² − σ²)² /
// (2 σ⁴), the EDF of each point for the model's dominant term (set on the
// curve): the goodness of fit the criterion compares.
double Pearson(std::vector<AllanPoint>& curve,
               const Model& m,
               double phase_points,
               double confidence) {
  SetIntervals(curve, &m, phase_points, confidence);
  double sum = 0.0;
  for (const AllanPoint& p : curve) {
    const double model = m.Avar(p.tau_s);
    const double d = p.avar - model;
    sum += p.edf * d * d / (2.0 * model * model);
  }
  return sum;
}

// The extra term `col` added to `start`: its τc (or P) searched with the
// weights of `start` fixed, on a grid that puts its peak at every cluster
// time (and half-way between) in [peak_lo_s, peak_hi_s], then by golden
// section in log τc between the best one's neighbours; the coefficients
// refitted with reweighting at the best, and the search repeated once about
// it with the new weights. Infinite cost when no grid point fits.
Fit SearchShape(std::vector<AllanPoint>& curve,
                const Fit& start,
                int col,
                TermMask allowed,
                TermMask signed_terms,
                double peak_lo_s,
                double peak_hi_s,
                double phase_points,
                const NoiseOptions& o) {
  const double peak = col == kGaussMarkov ? kGaussMarkovPeak : kSinusoidPeak;
  const TermMask allow = allowed | (1u << col);
  const TermMask required = 1u << col;
  std::vector<double> grid;
  for (std::size_t j = 0; j < curve.size(); ++j) {
    const double tau = curve[j].tau_s;
    if (tau < peak_lo_s || tau > peak_hi_s) continue;
    if (!grid.empty()) grid.push_back(std::sqrt(grid.back() * tau / peak));
    grid.push_back(tau / peak);
  }
  Fit fail;
  if (grid.size() < 3) return fail;
  Model shape = start.m;
  Fit fit = start;
  double lo = std::log(grid.front()), hi = std::log(grid.back());
  for (int round = 0; round < 2; ++round) {
    SetIntervals(curve, &fit.m, phase_points, o.allan.confidence);
    const std::vector<double> weight = ModelWeights(curve, fit.m);
    const auto cost_at = [&](double log_param) {
      Model m = shape;
      ShapeOf(m, col) = std::exp(log_param);
      return FitNonNegative(curve, weight, m, allow, signed_terms, required).cost;
    };
    double best = round == 0 ? std::log(grid.front()) : std::log(ShapeOf(fit.m, col));
    if (round == 0) {
      double best_cost = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < grid.size(); ++i) {
        const double c = cost_at(std::log(grid[i]));
        if (c < best_cost) {
          best_cost = c;
          best = std::log(grid[i]);
          lo = std::log(grid[i == 0 ? 0 : i - 1]);
          hi = std::log(grid[std::min(i + 1, grid.size() - 1)]);
        }
      }
      if (!std::isfinite(best_cost)) return fail;
    } else {
      const double here = std::log(ShapeOf(fit.m, col));
      const double step = std::log(2.0) / (2.0 * o.allan.points_per_octave);
      // Within the grid: the limits on where its peak may lie hold here too.
      lo = std::max(here - step, std::log(grid.front()));
      hi = std::min(here + step, std::log(grid.back()));
    }
    // Golden section on [lo, hi].
    constexpr double kGolden = 0.6180339887498949;
    double a = lo, b = hi;
    double x1 = b - kGolden * (b - a), x2 = a + kGolden * (b - a);
    double f1 = cost_at(x1), f2 = cost_at(x2);
    for (int it = 0; it < 24; ++it) {
      if (f1 < f2) {
        b = x2, x2 = x1, f2 = f1;
        x1 = b - kGolden * (b - a);
        f1 = cost_at(x1);
      } else {
        a = x1, x1 = x2, f1 = f2;
        x2 = a + kGolden * (b - a);
        f2 = cost_at(x2);
      }
    }
    const double found = f1 < f2 ? x1 : x2;
    if (round == 0 || std::isfinite(std::min(f1, f2))) best = found;
    ShapeOf(shape, col) = std::exp(best);
    const Fit next =
        FitTerms(curve, allow, phase_points, o, signed_terms, shape, required, &fit.m);
    if (!std::isfinite(next.cost)) return round == 0 ? fail : fit;
    fit = next;
  }
  return fit;
}

// The range of τc (or P) the curve allows about the fitted one: where the
// weighted cost, the other coefficients refitted, rises by at most the χ²
// quantile of one parameter (in independent points), searched outward in
// sixteenths of an octave up to four octaves each way, the crossing then
// by bisection.
TauRange ShapeInterval(const std::vector<AllanPoint>& curve,
                       const Fit& fit,
                       int col,
                       TermMask allowed,
                       TermMask signed_terms,
                       const NoiseOptions& o) {
  const double inflation = o.allan.points_per_octave / o.independent_points_per_octave;
  const std::vector<double> weight = ModelWeights(curve, fit.m);
  const double at = ShapeOf(fit.m, col);
  const auto cost_at = [&](double param) {
    Model m = fit.m;
    ShapeOf(m, col) = param;
    return FitNonNegative(curve, weight, m, allowed, signed_terms, 1u << col).cost;
  };
  const double limit =
      cost_at(at) + inflation * ChiSquareQuantile(o.allan.confidence, 1.0);
  // Outward in sixteenths of an octave to the first step beyond the limit,
  // then the crossing by bisection in log τ (a sinusoid's period is often
  // held to a fraction of a step).
  const auto edge = [&](double direction) {
    const double step = std::exp2(direction / 16.0);
    double inside = at;
    for (int i = 1; i <= 64; ++i) {
      const double p = inside * step;
      if (!(cost_at(p) <= limit)) {
        double a = std::log(inside), b = std::log(p);
        for (int it = 0; it < 12; ++it) {
          const double mid = 0.5 * (a + b);
          (cost_at(std::exp(mid)) <= limit ? a : b) = mid;
        }
        return std::exp(a);
      }
      inside = p;
    }
    return inside;
  };
  const TauRange r{edge(-1.0), edge(1.0)};
  return r;
}

// The least share of the fitted variance an extra term must carry at the
// cluster time where it carries most. The criterion alone, on the curve of
// a half-hour record whose short-τ points have intervals of ±0.4 %, admits
// sinusoids of 1 % of the variance that follow the record's own scatter
// there (neighbouring cluster times share their samples); a bump or a
// sinusoid the check would flag if left out carries a fifth of it or more.
constexpr double kExtraShare = 0.1;
// The widest interval of τc (or P), as the ratio of its limits, for the
// term to count as shown by the curve: two octaves.
constexpr double kExtraShapeRange = 4.0;

double LargestShare(const std::vector<AllanPoint>& curve, const Model& m, int col) {
  double largest = 0.0;
  for (const AllanPoint& p : curve) {
    largest = std::max(largest, m.Part(col, p.tau_s) / m.Avar(p.tau_s));
  }
  return largest;
}

// The extra terms the curve shows, added to the IEEE fit `base` one at a
// time while the Bayesian information criterion (Schwarz 1978) falls: each
// adds two parameters (its coefficient and its τc or P), and is kept when
// Pearson's statistic falls by more than 2 ln n_eff, both counted in
// independent points (the statistic and n divided by the same correlation
// factor as the covariance, NoiseOptions::independent_points_per_octave),
// and its coefficient is above zero by its interval. The bump's peak must
// lie an octave and a half beyond the curve's first cluster time
// (`first_tau_s`: a low-pass filter's roll-off, itself a Gauss-Markov
// process of τc = 1/(2πF), is not a bump) and four octaves before its last
// (its falling side seen); a sinusoid's anywhere from the second cluster
// time to four octaves before the last.
Fit AddExtraTerms(std::vector<AllanPoint>& curve,
                  const Fit& base,
                  TermMask signed_terms,
                  double first_tau_s,
                  double phase_points,
                  const NoiseOptions& o) {
  const double inflation = o.allan.points_per_octave / o.independent_points_per_octave;
  const double n_eff = static_cast<double>(curve.size()) / inflation;
  const double penalty = 2.0 * std::log(std::max(n_eff, std::numbers::e));
  const double z = std::sqrt(ChiSquareQuantile(o.allan.confidence, 1.0));
  const double last_tau_s = curve.back().tau_s;
  Fit best = base;
  double best_stat = Pearson(curve, best.m, phase_points, o.allan.confidence);
  TermMask in_model = IeeeTerms(base.m);
  for (int round = 0; round < 2; ++round) {
    Fit chosen;
    double chosen_stat = std::numeric_limits<double>::infinity();
    int chosen_col = -1;
    for (const int col : {kGaussMarkov, kSinusoid}) {
      if (in_model & (1u << col)) continue;
      if (col == kGaussMarkov && !o.model_gauss_markov) continue;
      if (col == kSinusoid && !o.model_sinusoid) continue;
      const double peak_lo =
          col == kGaussMarkov ? first_tau_s * std::exp2(1.5) : first_tau_s * 1.1;
      const Fit f = SearchShape(curve,
                                best,
                                col,
                                in_model,
                                signed_terms,
                                peak_lo,
                                last_tau_s / 16.0,
                                phase_points,
                                o);
      if (!std::isfinite(f.cost) || !(f.m.c[col] > z * std::sqrt(f.variance[col])) ||
          LargestShare(curve, f.m, col) < kExtraShare)
        continue;
      // Its τc (P) pinned down by the curve: a bump of τc far beyond the
      // cluster times it rises over is a random walk there, and would take
      // part of one.
      const TauRange shape =
          ShapeInterval(curve, f, col, in_model | (1u << col), signed_terms, o);
      if (!(shape.hi_s <= kExtraShapeRange * shape.lo_s)) continue;
      const double stat = Pearson(curve, f.m, phase_points, o.allan.confidence);
      if ((best_stat - stat) / inflation > penalty && stat < chosen_stat) {
        chosen = f;
        chosen_stat = stat;
        chosen_col = col;
      }
    }
    if (chosen_col < 0) break;
    best = chosen;
    best_stat = chosen_stat;
    in_model |= 1u << chosen_col;
  }
  // With both in the model, the first one's τc (or P) was searched without
  // the second and may straddle both humps: each is searched again over the
  // whole grid with the other's held, while the statistic falls.
  if ((in_model & (1u << kGaussMarkov)) && (in_model & (1u << kSinusoid))) {
    for (int cycle = 0; cycle < 3; ++cycle) {
      bool improved = false;
      for (const int col : {kGaussMarkov, kSinusoid}) {
        const double peak_lo =
            col == kGaussMarkov ? first_tau_s * std::exp2(1.5) : first_tau_s * 1.1;
        const Fit f = SearchShape(curve,
                                  best,
                                  col,
                                  in_model & ~(1u << col),
                                  signed_terms,
                                  peak_lo,
                                  last_tau_s / 16.0,
                                  phase_points,
                                  o);
        if (!std::isfinite(f.cost) || !(f.m.c[kGaussMarkov] > 0.0) ||
            !(f.m.c[kSinusoid] > 0.0))
          continue;
        const double stat = Pearson(curve, f.m, phase_points, o.allan.confidence);
        if (stat < best_stat * (1.0 - 1e-9)) {
          best = f;
          best_stat = stat;
          improved = true;
        }
      }
      if (!improved) break;
    }
  }
  SetIntervals(curve, &best.m, phase_points, o.allan.confidence);
  return best;
}

// The τ range an extra term was read from: the cluster times about its
// largest share of the fitted variance where its share is at least half of
// that largest.
TauRange ExtraRegion(const std::vector<AllanPoint>& curve, const Model& m, int col) {
  std::vector<double> share(curve.size());
  std::size_t top = 0;
  for (std::size_t j = 0; j < curve.size(); ++j) {
    share[j] = m.Part(col, curve[j].tau_s) / m.Avar(curve[j].tau_s);
    if (share[j] > share[top]) top = j;
  }
  std::size_t a = top, b = top;
  while (a > 0 && share[a - 1] >= 0.5 * share[top]) --a;
  while (b + 1 < curve.size() && share[b + 1] >= 0.5 * share[top]) ++b;
  return {curve[a].tau_s, curve[b].tau_s};
}

// The Gauss-Markov process and the sinusoid in the fitted model: value,
// interval, τc or P with the range the curve allows, and region.
void MeasureExtraTerms(const std::vector<AllanPoint>& curve,
                       const Fit& fit,
                       TermMask signed_terms,
                       const NoiseOptions& o,
                       AxisNoise& out) {
  TermMask allowed = IeeeTerms(fit.m);
  for (const int col : {kGaussMarkov, kSinusoid}) {
    if (fit.m.c[col] > 0.0) allowed |= 1u << col;
  }
  for (const int col : {kGaussMarkov, kSinusoid}) {
    if (!(fit.m.c[col] > 0.0)) continue;
    const RootInterval v =
        CoefficientInterval(fit.m.c[col], fit.variance[col], o.allan.confidence);
    const TauRange shape = ShapeInterval(curve, fit, col, allowed, signed_terms, o);
    const TauRange region = ExtraRegion(curve, fit.m, col);
    if (col == kGaussMarkov) {
      GaussMarkovTerm& g = out.gauss_markov;
      g.status = TermStatus::kMeasured;
      g.sigma = v.value;
      g.sigma_lo = v.lo;
      g.sigma_hi = v.hi;
      g.tau_c_s = fit.m.tau_c_s;
      g.tau_c_lo_s = shape.lo_s;
      g.tau_c_hi_s = shape.hi_s;
      g.tau_lo_s = region.lo_s;
      g.tau_hi_s = region.hi_s;
    } else {
      SinusoidTerm& s = out.sinusoid;
      s.status = TermStatus::kMeasured;
      s.amplitude = v.value;
      s.amplitude_lo = v.lo;
      s.amplitude_hi = v.hi;
      s.period_s = fit.m.period_s;
      s.period_lo_s = shape.lo_s;
      s.period_hi_s = shape.hi_s;
      s.tau_lo_s = region.lo_s;
      s.tau_hi_s = region.hi_s;
    }
  }
}

// Whether the curve's first k + 1 points look like a low-pass filter's
// roll-off. The Allan deviation of white noise through a first-order
// low-pass falls at every τ, its slope from about 0 steepening towards −½
// and never beyond; a Gauss-Markov bump or a sinusoid on white noise
// instead flattens or rises from −½ and falls steeper than −½ after its
// peak. So: the first local slope flatter than −½, none steeper than −½,
// and none flatter than a slope at a shorter τ, beyond its uncertainty (each point's
// relative standard deviation from its interval, taken as independent: lenient).
bool ShortEndRollsOff(const std::vector<AllanPoint>& curve,
                      std::size_t k,
                      double confidence) {
  const double z = std::sqrt(ChiSquareQuantile(confidence, 1.0));
  double steepest = std::numeric_limits<double>::infinity();
  for (std::size_t j = 0; j < k && j + 1 < curve.size(); ++j) {
    const AllanPoint& a = curve[j];
    const AllanPoint& b = curve[j + 1];
    const double span = std::log(b.tau_s / a.tau_s);
    const double sd_a = std::log(a.adev_hi / a.adev_lo) / (2.0 * z);
    const double sd_b = std::log(b.adev_hi / b.adev_lo) / (2.0 * z);
    const double slope = std::log(b.adev / a.adev) / span;
    const double se = std::hypot(sd_a, sd_b) / span;
    if (slope < -0.5 - z * se || slope > steepest + z * se) return false;
    // The roll-off is strongest at the first cluster time: flatter than −½
    // there (a bump on white noise starts at −½).
    if (j == 0 && !(slope > -0.5 + z * se)) return false;
    steepest = std::min(steepest, slope);
  }
  return true;
}

// The low-pass filter's φ that best fits `curve` with the columns of `fit`
// (the IEEE terms and the extra terms it has), by golden section with the
// weights of `fit` held, then the coefficients refitted with reweighting at
// it. Infinite cost when no φ fits. φ ranges over filters whose time
// constant τ0/ln(1/φ) is at most the curve's first cluster time (the
// short end cut off holds the roll-off): white noise through a slower
// filter is a Gauss-Markov process, a bump, not a filter's roll-off.
Fit SearchLowpass(std::vector<AllanPoint>& curve,
                  const Fit& fit,
                  double tau0_s,
                  double phase_points,
                  const NoiseOptions& o) {
  TermMask allowed = kIeeeTerms & ~(1u << kQuantIndex), required = 0;
  for (const int col : {kGaussMarkov, kSinusoid}) {
    if (fit.m.c[col] > 0.0) allowed |= 1u << col, required |= 1u << col;
  }
  SetIntervals(curve, &fit.m, phase_points, o.allan.confidence);
  const std::vector<double> weight = ModelWeights(curve, fit.m);
  Model shape = fit.m;
  shape.tau0_s = tau0_s;
  const auto cost_at = [&](double phi) {
    Model m = shape;
    m.lowpass_phi = phi;
    return FitNonNegative(curve, weight, m, allowed, 0, required).cost;
  };
  constexpr double kGolden = 0.6180339887498949;
  double a = 0.0, b = std::exp(-tau0_s / curve.front().tau_s);
  double x1 = b - kGolden * (b - a), x2 = a + kGolden * (b - a);
  double f1 = cost_at(x1), f2 = cost_at(x2);
  for (int it = 0; it < 30; ++it) {
    if (f1 < f2) {
      b = x2, x2 = x1, f2 = f1;
      x1 = b - kGolden * (b - a);
      f1 = cost_at(x1);
    } else {
      a = x1, x1 = x2, f1 = f2;
      x2 = a + kGolden * (b - a);
      f2 = cost_at(x2);
    }
  }
  shape.lowpass_phi = f1 < f2 ? x1 : x2;
  if (!std::isfinite(std::min(f1, f2))) return Fit{};
  return FitTerms(curve, allowed, phase_points, o, 0, shape, required, &fit.m);
}

}  // namespace

std::string_view ToString(TermStatus status) {
  switch (status) {
    case TermStatus::kMeasured:
      return "measured";
    case TermStatus::kNotSeen:
      return "not_seen";
    case TermStatus::kMasked:
      return "masked";
    case TermStatus::kDisagrees:
      return "disagrees";
  }
  return "?";
}

std::string NoiseOptions::Validate() const {
  if (std::string bad = allan.Validate(); !bad.empty()) return "allan." + bad;
  if (!(dominance > 0.0 && dominance < 1.0)) return "dominance must be in (0, 1)";
  if (min_region_points < 1) return "min_region_points must be at least 1";
  if (fit_iterations < 0) return "fit_iterations must not be negative";
  if (!(independent_points_per_octave > 0.0 &&
        independent_points_per_octave <= allan.points_per_octave)) {
    return "independent_points_per_octave must be in (0, allan.points_per_octave]";
  }
  if (!(max_misfit_share >= 0.0 && max_misfit_share <= 1.0))
    return "max_misfit_share must be in [0, 1]";
  return {};
}

double GaussMarkovAvar(double sigma2, double tau_c_s, double tau_s) {
  if (!(sigma2 > 0.0 && tau_c_s > 0.0 && tau_s > 0.0)) return 0.0;
  const double x = tau_s / tau_c_s;
  // The bracket 1 − (3 − 4e^{−x} + e^{−2x}) / (2x) loses its digits to
  // cancellation for small x: its series there, x²/3 − x³/4 + 7x⁴/60.
  const double bracket =
      x < 1e-3 ? x * x * (1.0 / 3.0 - x * (0.25 - x * 7.0 / 60.0))
               : 1.0 - (-4.0 * std::expm1(-x) + std::expm1(-2.0 * x)) / (2.0 * x);
  return 2.0 * sigma2 / x * bracket;
}

double SinusoidAvar(double amplitude2, double period_s, double tau_s) {
  if (!(amplitude2 > 0.0 && period_s > 0.0 && tau_s > 0.0)) return 0.0;
  const double x = std::numbers::pi * tau_s / period_s;
  const double s = std::sin(x);
  return amplitude2 * s * s * s * s / (x * x);
}

double AxisNoise::FittedAvar(double tau_s) const {
  double sum = 0.0;
  for (int t = 0; t < kTerms; ++t) sum += fit_avar_coefficients[t] * Basis(t, tau_s);
  sum += GaussMarkovAvar(fit_gauss_markov.sigma2, fit_gauss_markov.tau_c_s, tau_s);
  sum += SinusoidAvar(fit_sinusoid.amplitude2, fit_sinusoid.period_s, tau_s);
  return sum;
}

namespace internal {

AxisNoise AnalyseAxis(std::vector<AllanPoint> curve,
                      double phase_points,
                      const NoiseOptions& o) {
  AxisNoise out;
  out.gauss_markov.modelled = o.model_gauss_markov;
  out.sinusoid.modelled = o.model_sinusoid;
  // One fit with every IEEE term (non-negative: those the curve does not
  // support come out zero or small), then the Gauss-Markov process and the
  // sinusoid where the criterion admits them; each term is reported only
  // where it dominates. Refitting without the terms not seen would push
  // their variance into their neighbours (a bias instability under the
  // white noise and random walk would inflate both).
  const double first_tau_s = curve.front().tau_s;
  const double tau0_s = first_tau_s / static_cast<double>(curve.front().m);
  const auto fit_model = [&](std::vector<AllanPoint>& points, TermMask signed_terms) {
    const Fit base = FitTerms(points, kIeeeTerms, phase_points, o, signed_terms);
    if (!std::isfinite(base.cost)) return base;
    return AddExtraTerms(points, base, signed_terms, first_tau_s, phase_points, o);
  };
  Fit fit = fit_model(curve, 0);
  if (!std::isfinite(fit.cost)) {
    fit = Fit{};
    SetIntervals(curve, nullptr, phase_points, o.allan.confidence);
  }
  ModelCheck check = CheckModel(curve, fit.m, o);
  // A model that misses the curve: when its short-τ end rolls off below the
  // model like a low-pass filter's, the fit starts further out, at the
  // first cluster time from which the model fits and that lies inside the
  // curve's interval (at most half the curve left out).
  std::size_t from = 0;
  TermMask signed_terms = 0;
  // A short end that rolls off (flatter than −½ at the first cluster time)
  // under a model with an extra term is tried cut too, even where that model
  // passes the check: the term may stand in for a filter (a bump of τc near
  // the filter's, whose output is itself a Gauss-Markov process) and take N
  // with it. The cut is kept when it fits.
  const bool rolls_off = (fit.m.c[kGaussMarkov] > 0.0 || fit.m.c[kSinusoid] > 0.0) &&
                         ShortEndRollsOff(curve, 1, o.allan.confidence);
  for (std::size_t k = 1; (!check.fits || rolls_off) && k <= curve.size() / 2 &&
                          ShortEndRollsOff(curve, k, o.allan.confidence);
       ++k) {
    std::vector<AllanPoint> kept(curve.begin() + static_cast<std::ptrdiff_t>(k),
                                 curve.end());
    // Beyond a few correlation times of a first-order low-pass the white
    // noise it filtered has σ²(τ) = N²/τ − D/τ² up to terms in φ^m (its
    // output is an AR(1) sequence, whose sums have a closed-form variance):
    // the quantisation's basis with a negative coefficient, allowed here
    // (never reported: a term is measured only where it is positive).
    // That remnant is exact with the filter's own σ²(τ) for the white
    // noise (FilteredWhite, φ fitted), which ties D to N² and leaves N less
    // entangled with a bump rising just beyond: tried first; the signed
    // term serves a roll-off that is not first-order.
    const TermMask quant = 1u << kQuantIndex;
    const Fit ieee = FitTerms(kept, kIeeeTerms, phase_points, o, quant);
    if (!std::isfinite(ieee.cost)) continue;
    const Fit asymptotic = AddExtraTerms(kept, ieee, quant, first_tau_s, phase_points, o);
    // φ searched with the IEEE terms, the extra terms added after; when that
    // misses (a bump rising just beyond the roll-off bends φ), searched with
    // the extra terms of the asymptotic fit.
    const auto filter_from = [&](const Fit& seed) {
      Fit f = SearchLowpass(kept, seed, tau0_s, phase_points, o);
      if (!std::isfinite(f.cost)) return f;
      f = AddExtraTerms(kept, f, 0, first_tau_s, phase_points, o);
      if (f.m.c[kGaussMarkov] > 0.0 || f.m.c[kSinusoid] > 0.0) {
        const Fit again = SearchLowpass(kept, f, tau0_s, phase_points, o);
        if (std::isfinite(again.cost)) f = again;
      }
      return f;
    };
    const auto accept = [&](const Fit& f, TermMask signs) {
      if (!std::isfinite(f.cost)) return false;
      const ModelCheck c = CheckModel(kept, f.m, o);
      // The short end cut off lies below the positive terms carried to it
      // (the white noise line, unfiltered): a roll-off, not an excess.
      Model positive = f.m;
      positive.lowpass_phi = 0.0;
      for (double& c_t : positive.c) c_t = std::max(c_t, 0.0);
      bool below = true;
      for (std::size_t j = 0; j < k; ++j) {
        below = below && curve[j].adev < std::sqrt(positive.Avar(curve[j].tau_s));
      }
      // The cut goes on while the first cluster time kept still lies
      // outside: what is left of the roll-off there pulls N down.
      const bool starts_inside =
          c.disagree.empty() || c.disagree.front().lo_s > kept.front().tau_s;
      if (!c.fits || !below || !starts_inside) return false;
      from = k;
      fit = f;
      check = c;
      signed_terms = signs;
      return true;
    };
    if (accept(filter_from(ieee), 0)) break;
    if (std::isfinite(asymptotic.cost) && accept(filter_from(asymptotic), 0)) break;
    if (accept(asymptotic, quant)) break;
  }
  if (from > 0) SetIntervals(curve, &fit.m, phase_points, o.allan.confidence);
  check.excluded = static_cast<int>(from);
  for (int t = 0; t < kTerms; ++t) out.fit_avar_coefficients[t] = fit.m.c[t];
  if (fit.m.c[kGaussMarkov] > 0.0)
    out.fit_gauss_markov = {fit.m.c[kGaussMarkov], fit.m.tau_c_s};
  if (fit.m.c[kSinusoid] > 0.0) out.fit_sinusoid = {fit.m.c[kSinusoid], fit.m.period_s};

  const std::vector<AllanPoint> kept(curve.begin() + static_cast<std::ptrdiff_t>(from),
                                     curve.end());
  MeasureTerms(kept, fit, o, out);
  MeasureExtraTerms(kept, fit, signed_terms, o, out);
  // A term whose region meets a stretch where the model misses the curve is
  // not presented as measured.
  const auto meets_misfit = [&check](double lo_s, double hi_s) {
    for (const TauRange& r : check.disagree) {
      if (r.lo_s <= hi_s && r.hi_s >= lo_s) return true;
    }
    return false;
  };
  if (!check.fits) {
    for (TermEstimate& e : out.terms) {
      if (e.status != TermStatus::kMeasured || !meets_misfit(e.tau_lo_s, e.tau_hi_s))
        continue;
      e = TermEstimate{};
      e.status = TermStatus::kDisagrees;
    }
    GaussMarkovTerm& g = out.gauss_markov;
    if (g.status == TermStatus::kMeasured && meets_misfit(g.tau_lo_s, g.tau_hi_s)) {
      g = GaussMarkovTerm{};
      g.modelled = o.model_gauss_markov;
      g.status = TermStatus::kDisagrees;
    }
    SinusoidTerm& sn = out.sinusoid;
    if (sn.status == TermStatus::kMeasured && meets_misfit(sn.tau_lo_s, sn.tau_hi_s)) {
      sn = SinusoidTerm{};
      sn.modelled = o.model_sinusoid;
      sn.status = TermStatus::kDisagrees;
    }
  }
  BoundTerms(kept, fit, (phase_points - 1.0) * tau0_s, o, out);
  out.check = std::move(check);
  out.curve = std::move(curve);
  return out;
}

}  // namespace internal
}  // namespace mpcal
