// What the fit of an axis reports of the IEEE terms (term_measure.h): each
// term measured where it dominates and stands above zero by its interval,
// the upper bound of each term not measured with the record that would show
// it, from a forecast of the same fit on a longer record, and the cluster
// times where the model misses the curve.
#include "noise/term_measure.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "mpcal/noise.h"
#include "noise/noise_fit.h"
#include "noise/term_model.h"

namespace mpcal::internal::noise_fit {
namespace {

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

// IEEE 952 reads a term off the stretch of the curve where its slope holds,
// and where that stretch begins and ends is a choice the reading depends on.
// The term read on a stretch [first, last] of the curve: what the curve's
// variance leaves when the other fitted columns are taken away, over the
// term's own shape, averaged with the fit's weights (1 / var of each
// reading); and the variance of that average, inflated for correlated τ as
// the fit's own.
struct RegionReading {
  double c = 0.0;
  double variance = std::numeric_limits<double>::infinity();
};

RegionReading ReadOnRegion(const std::vector<AllanPoint>& curve,
                           const Model& m,
                           int t,
                           std::size_t first,
                           std::size_t last,
                           const NoiseOptions& o) {
  double sum_w = 0.0, sum_wr = 0.0;
  for (std::size_t i = first; i <= last; ++i) {
    const double tau = curve[i].tau_s;
    const double shape = m.Column(t, tau);
    const double model = m.Avar(tau);
    if (!(shape > 0.0 && model > 0.0)) continue;
    const double reading = (curve[i].avar - (model - m.Part(t, tau))) / shape;
    const double w = curve[i].edf * shape * shape / (2.0 * model * model);
    sum_w += w;
    sum_wr += w * reading;
  }
  if (!(sum_w > 0.0)) return {};
  return {sum_wr / sum_w,
          o.allan.points_per_octave / o.independent_points_per_octave / sum_w};
}

// The choice of region's part of a measured coefficient's variance: the
// term read on its region and on that region shortened by an octave at
// either end (while min_region_points remain); the largest squared distance
// of a reading from the fitted coefficient beyond the reading's own
// variance (the curve's uncertainty, counted once, in the fit's). Zero when
// the readings agree with the fit within their noise, as they do when the
// model holds across the region.
double RegionChoiceVariance(const std::vector<AllanPoint>& curve,
                            const Model& m,
                            int t,
                            const std::vector<std::size_t>& region,
                            const NoiseOptions& o) {
  const std::size_t first = region.front(), last = region.back();
  const auto octave = static_cast<std::size_t>(o.allan.points_per_octave);
  const auto min_points = static_cast<std::size_t>(o.min_region_points);
  std::vector<std::pair<std::size_t, std::size_t>> stretches = {{first, last}};
  if (last - first + 1 >= min_points + octave) {
    stretches.emplace_back(first + octave, last);
    stretches.emplace_back(first, last - octave);
  }
  double excess = 0.0;
  for (const auto& [lo, hi] : stretches) {
    const RegionReading r = ReadOnRegion(curve, m, t, lo, hi, o);
    if (!std::isfinite(r.variance)) continue;
    const double d = r.c - m.c[t];
    excess = std::max(excess, d * d - r.variance);
  }
  return excess;
}

}  // namespace

RootInterval CoefficientInterval(double c, double variance, double confidence) {
  const double lo_p = 0.5 * (1.0 - confidence);
  const double nu = std::max(2.0 * c * c / variance, 0.1);
  return {std::sqrt(c),
          std::sqrt(c * nu / ChiSquareQuantile(1.0 - lo_p, nu)),
          std::sqrt(c * nu / ChiSquareQuantile(lo_p, nu))};
}

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
    // The interval carries the curve's uncertainty (the fit's variance) and
    // that of the choice of region.
    const double variance =
        fit.variance[t] + RegionChoiceVariance(curve, fit.m, t, region, o);
    const RootInterval v = CoefficientInterval(c, variance, o.allan.confidence);
    e.status = TermStatus::kMeasured;
    e.value = v.value;
    e.lo = v.lo;
    e.hi = v.hi;
    e.tau_lo_s = curve[region.front()].tau_s;
    e.tau_hi_s = curve[region.back()].tau_s;
  }
}

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

}  // namespace mpcal::internal::noise_fit
