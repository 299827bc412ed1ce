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

constexpr int kTerms = kNoiseTermCount;
using TermMask = unsigned;
using Coefficients = std::array<double, kTerms>;  // Q², N², B², K², R²
constexpr int kRampIndex = static_cast<int>(NoiseTerm::kRateRamp);
constexpr int kQuantIndex = static_cast<int>(NoiseTerm::kQuantisation);

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

double Model(const Coefficients& c, double tau_s) {
  double sum = 0.0;
  for (int t = 0; t < kTerms; ++t) sum += c[t] * Basis(t, tau_s);
  return sum;
}

struct Fit {
  Coefficients c{};
  Coefficients variance{};  // of each coefficient
  double cost = std::numeric_limits<double>::infinity();
};

// Non-negative least squares over the terms in `allowed`: the optimum lies
// on some support set where the unconstrained optimum is positive, so with
// five terms every subset is tried (exact, and 31 tiny solves).
// `signed_terms`: those that may come out negative (the roll-off of a
// low-pass filter beyond its short-τ end, see AnalyseAxis).
Fit FitNonNegative(const std::vector<AllanPoint>& curve,
                   const std::vector<double>& weight,
                   TermMask allowed,
                   TermMask signed_terms = 0) {
  Fit best;
  const int rows = static_cast<int>(curve.size());
  for (TermMask set = 1; set < (1u << kTerms); ++set) {
    if ((set & ~allowed) != 0) continue;
    std::vector<int> cols;
    for (int t = 0; t < kTerms; ++t) {
      if (set & (1u << t)) cols.push_back(t);
    }
    const int k = static_cast<int>(cols.size());
    if (k > rows) continue;
    Eigen::MatrixXd a(rows, k);
    Eigen::VectorXd b(rows);
    for (int j = 0; j < rows; ++j) {
      const double sw = std::sqrt(weight[j]);
      for (int i = 0; i < k; ++i) a(j, i) = sw * Basis(cols[i], curve[j].tau_s);
      b(j) = sw * curve[j].avar;
    }
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
    bool model_positive = true;
    for (int j = 0; j < rows; ++j)
      model_positive = model_positive && (a.row(j) * x)(0) > 0.0;
    if (!model_positive) continue;
    const double cost = (a * x - b).squaredNorm();
    if (cost >= best.cost) continue;
    best = Fit{};
    best.cost = cost;
    const Eigen::MatrixXd cov_s = (as.transpose() * as).inverse();
    for (int i = 0; i < k; ++i) {
      best.c[cols[i]] = x(i);
      best.variance[cols[i]] = cov_s(i, i) / (scale(i) * scale(i));
    }
  }
  return best;
}

int Dominant(const Coefficients& c, double tau_s) {
  int arg = static_cast<int>(NoiseTerm::kWhiteNoise);
  double largest = -1.0;
  for (int t = 0; t < kTerms; ++t) {
    const double v = c[t] * Basis(t, tau_s);
    if (v > largest) largest = v, arg = t;
  }
  return arg;
}

// EDF and interval of every point for the dominant term of `c` (white noise
// before any fit).
void SetIntervals(std::vector<AllanPoint>& curve,
                  const Coefficients* c,
                  double phase_points,
                  double confidence) {
  const double lo_p = 0.5 * (1.0 - confidence);
  for (AllanPoint& p : curve) {
    p.dominant =
        c ? static_cast<NoiseTerm>(Dominant(*c, p.tau_s)) : NoiseTerm::kWhiteNoise;
    p.edf =
        std::min(OverlappingAllanEdf(phase_points, static_cast<double>(p.m), p.dominant),
                 static_cast<double>(p.terms));
    p.adev_lo = std::sqrt(p.avar * p.edf / ChiSquareQuantile(1.0 - lo_p, p.edf));
    p.adev_hi = std::sqrt(p.avar * p.edf / ChiSquareQuantile(lo_p, p.edf));
  }
}

// The reweighted fit: weights 1 / var(σ̂²) = edf / (2 model²), the model's
// variance rather than the data's (weights from the data would pull the fit
// towards the points that came out low).
Fit FitTerms(std::vector<AllanPoint>& curve,
             TermMask allowed,
             double phase_points,
             const NoiseOptions& o,
             TermMask signed_terms = 0) {
  std::vector<double> weight(curve.size());
  const double inflation = o.allan.points_per_octave / o.independent_points_per_octave;
  SetIntervals(curve, nullptr, phase_points, o.allan.confidence);
  for (std::size_t j = 0; j < curve.size(); ++j) {
    weight[j] = curve[j].edf / (2.0 * curve[j].avar * curve[j].avar);
  }
  Fit fit = FitNonNegative(curve, weight, allowed, signed_terms);
  for (int it = 0; it < o.fit_iterations && std::isfinite(fit.cost); ++it) {
    SetIntervals(curve, &fit.c, phase_points, o.allan.confidence);
    for (std::size_t j = 0; j < curve.size(); ++j) {
      const double model = Model(fit.c, curve[j].tau_s);
      weight[j] = curve[j].edf / (2.0 * model * model);
    }
    const Fit next = FitNonNegative(curve, weight, allowed, signed_terms);
    if (!std::isfinite(next.cost)) break;
    fit = next;
  }
  if (std::isfinite(fit.cost))
    SetIntervals(curve, &fit.c, phase_points, o.allan.confidence);
  for (double& v : fit.variance) v *= inflation;
  return fit;
}

// Points where term t carries at least `dominance` of the fitted variance.
std::vector<std::size_t> DominatedPoints(const std::vector<AllanPoint>& curve,
                                         const Coefficients& c,
                                         int t,
                                         double dominance) {
  std::vector<std::size_t> out;
  for (std::size_t j = 0; j < curve.size(); ++j) {
    const double total = Model(c, curve[j].tau_s);
    if (c[t] > 0.0 && c[t] * Basis(t, curve[j].tau_s) >= dominance * total)
      out.push_back(j);
  }
  return out;
}

// What the fit would give on a record of `record_s` whose curve is the model
// `c` (exactly): how many cluster times term t carries `dominance` of the
// variance at, and the variance of its coefficient, from the same weighted
// least squares (weights edf / (2 model²), over the terms of `c` with t,
// inflated for correlated τ) that FitTerms runs on a measured curve.
struct Forecast {
  int region_points = 0;
  double variance = std::numeric_limits<double>::infinity();
};

Forecast ForecastFit(
    const Coefficients& c, int t, double record_s, const NoiseOptions& o, double tau0_s) {
  const auto samples = static_cast<std::int64_t>(record_s / tau0_s);
  const std::vector<std::int64_t> ms = internal::ClusterSizes(samples, o.allan);
  const double n = static_cast<double>(samples + 1);
  std::vector<int> cols;
  for (int j = 0; j < kTerms; ++j) {
    if (c[j] > 0.0) cols.push_back(j);
  }
  const auto k = static_cast<Eigen::Index>(cols.size());
  Eigen::MatrixXd a(static_cast<Eigen::Index>(ms.size()), k);
  Forecast f;
  for (std::size_t r = 0; r < ms.size(); ++r) {
    const double tau = static_cast<double>(ms[r]) * tau0_s;
    const double model = Model(c, tau);
    const auto dominant = static_cast<NoiseTerm>(Dominant(c, tau));
    const double edf = OverlappingAllanEdf(n, static_cast<double>(ms[r]), dominant);
    const double sw = std::sqrt(edf / 2.0) / model;
    for (Eigen::Index i = 0; i < k; ++i) {
      a(static_cast<Eigen::Index>(r), i) = sw * Basis(cols[i], tau);
    }
    f.region_points += c[t] * Basis(t, tau) >= o.dominance * model;
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
double RecordNeeded(Coefficients c,
                    int t,
                    double c_t,
                    double record_s,
                    double tau0_s,
                    const NoiseOptions& o) {
  c[t] = c_t;
  // Above zero by the interval (z) in 9 records of 10: z + the 90 % normal
  // quantile standard deviations of the coefficient.
  constexpr double kPowerQuantile = 1.2815515655446004;
  const double z = std::sqrt(ChiSquareQuantile(o.allan.confidence, 1.0)) + kPowerQuantile;
  for (double length = record_s * std::exp2(0.125); length < 1e9;
       length *= std::exp2(0.125)) {
    const Forecast f = ForecastFit(c, t, length, o, tau0_s);
    if (f.region_points >= o.min_region_points && c_t > z * std::sqrt(f.variance))
      return length;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

// Measured terms: value and interval from the coefficient's variance, as a
// scaled χ² with ν = 2 c² / var(c) degrees of freedom (exact for one point;
// keeps the interval positive).
void MeasureTerms(const std::vector<AllanPoint>& curve,
                  const Fit& fit,
                  const NoiseOptions& o,
                  AxisNoise& out) {
  const double z = std::sqrt(ChiSquareQuantile(o.allan.confidence, 1.0));
  const double lo_p = 0.5 * (1.0 - o.allan.confidence);
  for (int t = 0; t < kTerms; ++t) {
    const std::vector<std::size_t> region = DominatedPoints(curve, fit.c, t, o.dominance);
    const double c = fit.c[t];
    const bool significant = c > z * std::sqrt(fit.variance[t]);
    if (static_cast<int>(region.size()) < o.min_region_points || !significant) continue;
    TermEstimate& e = out.terms[t];
    const double nu = std::max(2.0 * c * c / fit.variance[t], 0.1);
    e.status = TermStatus::kMeasured;
    e.value = std::sqrt(c);
    e.lo = std::sqrt(c * nu / ChiSquareQuantile(1.0 - lo_p, nu));
    e.hi = std::sqrt(c * nu / ChiSquareQuantile(lo_p, nu));
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
  Coefficients others = fit.c;
  if (!out.term(NoiseTerm::kRateRamp).value) others[kRampIndex] = 0.0;
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

// The fitted model `c` against the curve: the cluster times where its σ(τ)
// lies outside the curve's interval, and their runs.
ModelCheck CheckModel(const std::vector<AllanPoint>& curve,
                      const Coefficients& c,
                      const NoiseOptions& o) {
  ModelCheck check;
  check.points = static_cast<int>(curve.size());
  if (curve.empty()) return check;
  check.from_tau_s = curve.front().tau_s;
  bool in_run = false;
  for (const AllanPoint& p : curve) {
    const double fitted = std::sqrt(Model(c, p.tau_s));
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
  // One fit with every term (non-negative: those the curve does not support
  // come out zero or small); then each is reported only where it dominates.
  // Refitting without the terms not seen would push their variance into
  // their neighbours (a bias instability under the white noise and random
  // walk would inflate both).
  const TermMask all = (1u << kTerms) - 1;
  Fit fit = FitTerms(curve, all, phase_points, o);
  if (!std::isfinite(fit.cost)) {
    fit = Fit{};
    SetIntervals(curve, nullptr, phase_points, o.allan.confidence);
  }
  ModelCheck check = CheckModel(curve, fit.c, o);
  // A model that misses the curve: when its short-τ end rolls off below the
  // model like a low-pass filter's, the fit starts further out, at the
  // first cluster time from which the model fits and that lies inside the
  // curve's interval (at most half the curve left out).
  std::size_t from = 0;
  for (std::size_t k = 1; !check.fits && k <= curve.size() / 2 &&
                          ShortEndRollsOff(curve, k, o.allan.confidence);
       ++k) {
    std::vector<AllanPoint> kept(curve.begin() + static_cast<std::ptrdiff_t>(k),
                                 curve.end());
    // Beyond a few correlation times of a first-order low-pass the white
    // noise it filtered has σ²(τ) = N²/τ − D/τ² up to terms in φ^m (its
    // output is an AR(1) sequence, whose sums have a closed-form variance):
    // the quantisation's basis with a negative coefficient, allowed here
    // (never reported: a term is measured only where it is positive).
    const Fit f = FitTerms(kept, all, phase_points, o, 1u << kQuantIndex);
    if (!std::isfinite(f.cost)) continue;
    const ModelCheck c = CheckModel(kept, f.c, o);
    // The short end cut off lies below the positive terms carried to it
    // (the white noise line): a roll-off, not an excess.
    Coefficients positive = f.c;
    for (double& c_t : positive) c_t = std::max(c_t, 0.0);
    bool below = true;
    for (std::size_t j = 0; j < k; ++j) {
      below = below && curve[j].adev < std::sqrt(Model(positive, curve[j].tau_s));
    }
    // The cut goes on while the first cluster time kept still lies outside:
    // the roll-off fades as 1/τ, and what is left of it pulls N down.
    const bool starts_inside =
        c.disagree.empty() || c.disagree.front().lo_s > kept.front().tau_s;
    if (!c.fits || !below || !starts_inside) continue;
    from = k;
    fit = f;
    check = c;
  }
  if (from > 0) SetIntervals(curve, &fit.c, phase_points, o.allan.confidence);
  check.excluded = static_cast<int>(from);
  for (int t = 0; t < kTerms; ++t) out.fit_avar_coefficients[t] = fit.c[t];

  const std::vector<AllanPoint> kept(curve.begin() + static_cast<std::ptrdiff_t>(from),
                                     curve.end());
  MeasureTerms(kept, fit, o, out);
  // A term whose region meets a stretch where the model misses the curve is
  // not presented as measured.
  if (!check.fits) {
    for (TermEstimate& e : out.terms) {
      if (e.status != TermStatus::kMeasured) continue;
      for (const TauRange& r : check.disagree) {
        if (r.lo_s <= e.tau_hi_s && r.hi_s >= e.tau_lo_s) {
          e = TermEstimate{};
          e.status = TermStatus::kDisagrees;
          break;
        }
      }
    }
  }
  const double tau0_s = curve.front().tau_s / static_cast<double>(curve.front().m);
  BoundTerms(kept, fit, (phase_points - 1.0) * tau0_s, o, out);
  out.check = std::move(check);
  out.curve = std::move(curve);
  return out;
}

}  // namespace internal
}  // namespace mpcal
