// The Gauss-Markov process and the sinusoid (extra_terms.h): each one's τc
// or period searched, admitted by the Bayesian information criterion where
// the curve pins it down, and reported with the range of τc or period the
// curve allows and the cluster times it was read from.
#include "noise/extra_terms.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "mpcal/noise.h"
#include "noise/term_measure.h"
#include "noise/term_model.h"

namespace mpcal::internal::noise_fit {
namespace {

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
    const LineMinimum found = GoldenSection(cost_at, lo, hi, 24);
    if (round == 0 || std::isfinite(found.cost)) best = found.at;
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

// What the extra terms are searched over and judged by: the curve, the
// terms allowed a negative coefficient, where a peak may lie, and the
// criterion's penalty and the interval's z.
struct ExtraSearch {
  std::vector<AllanPoint>& curve;
  TermMask signed_terms;
  double first_tau_s;
  double phase_points;
  const NoiseOptions& o;
  double inflation;  // cluster times per independent point
  double penalty;    // the criterion's 2 ln n_eff, in independent points
  double z;          // the interval's half-width in standard deviations
};

// The extra term `col` searched into `from`, with the terms `in_model`
// beside it: its peak an octave and a half beyond the first cluster time
// for a bump, from the second for a sinusoid, up to four octaves before the
// last.
Fit SearchExtra(const ExtraSearch& s, const Fit& from, int col, TermMask in_model) {
  const double peak_lo =
      col == kGaussMarkov ? s.first_tau_s * std::exp2(1.5) : s.first_tau_s * 1.1;
  return SearchShape(s.curve,
                     from,
                     col,
                     in_model,
                     s.signed_terms,
                     peak_lo,
                     s.curve.back().tau_s / 16.0,
                     s.phase_points,
                     s.o);
}

// Whether the curve shows the term `col` of `f`: its coefficient above zero
// by its interval, a large enough share of the variance somewhere, and its
// τc (P) pinned down by the curve (a bump of τc far beyond the cluster
// times it rises over is a random walk there, and would take part of one).
bool Shown(const ExtraSearch& s, const Fit& f, int col, TermMask in_model) {
  if (!std::isfinite(f.cost) || !(f.m.c[col] > s.z * std::sqrt(f.variance[col])) ||
      LargestShare(s.curve, f.m, col) < kExtraShare)
    return false;
  const TauRange shape =
      ShapeInterval(s.curve, f, col, in_model | (1u << col), s.signed_terms, s.o);
  return shape.hi_s <= kExtraShapeRange * shape.lo_s;
}

// One round: of the extra terms not yet in the model, the one the curve
// shows that lowers Pearson's statistic most, when it lowers it by more than
// the criterion's penalty, added to `best`. False when none is.
bool AddBestExtraTerm(const ExtraSearch& s,
                      Fit& best,
                      double& best_stat,
                      TermMask& in_model) {
  Fit chosen;
  double chosen_stat = std::numeric_limits<double>::infinity();
  int chosen_col = -1;
  for (const int col : {kGaussMarkov, kSinusoid}) {
    const bool modelled =
        col == kGaussMarkov ? s.o.model_gauss_markov : s.o.model_sinusoid;
    if ((in_model & (1u << col)) || !modelled) continue;
    const Fit f = SearchExtra(s, best, col, in_model);
    if (!Shown(s, f, col, in_model)) continue;
    const double stat = Pearson(s.curve, f.m, s.phase_points, s.o.allan.confidence);
    if ((best_stat - stat) / s.inflation > s.penalty && stat < chosen_stat) {
      chosen = f;
      chosen_stat = stat;
      chosen_col = col;
    }
  }
  if (chosen_col < 0) return false;
  best = chosen;
  best_stat = chosen_stat;
  in_model |= 1u << chosen_col;
  return true;
}

// With both in the model, the first one's τc (or P) was searched without
// the second and may straddle both humps: each is searched again over the
// whole grid with the other's held, while the statistic falls.
void SearchBothAgain(const ExtraSearch& s,
                     TermMask in_model,
                     Fit& best,
                     double& best_stat) {
  for (int cycle = 0; cycle < 3; ++cycle) {
    bool improved = false;
    for (const int col : {kGaussMarkov, kSinusoid}) {
      const Fit f = SearchExtra(s, best, col, in_model & ~(1u << col));
      if (!std::isfinite(f.cost) || !(f.m.c[kGaussMarkov] > 0.0) ||
          !(f.m.c[kSinusoid] > 0.0))
        continue;
      const double stat = Pearson(s.curve, f.m, s.phase_points, s.o.allan.confidence);
      if (stat < best_stat * (1.0 - 1e-9)) {
        best = f;
        best_stat = stat;
        improved = true;
      }
    }
    if (!improved) break;
  }
}

}  // namespace

Fit AddExtraTerms(std::vector<AllanPoint>& curve,
                  const Fit& base,
                  TermMask signed_terms,
                  double first_tau_s,
                  double phase_points,
                  const NoiseOptions& o) {
  const double inflation = o.allan.points_per_octave / o.independent_points_per_octave;
  const double n_eff = static_cast<double>(curve.size()) / inflation;
  const ExtraSearch s{curve,
                      signed_terms,
                      first_tau_s,
                      phase_points,
                      o,
                      inflation,
                      2.0 * std::log(std::max(n_eff, std::numbers::e)),
                      std::sqrt(ChiSquareQuantile(o.allan.confidence, 1.0))};
  Fit best = base;
  double best_stat = Pearson(curve, best.m, phase_points, o.allan.confidence);
  TermMask in_model = IeeeTerms(base.m);
  for (int round = 0; round < 2; ++round) {
    if (!AddBestExtraTerm(s, best, best_stat, in_model)) break;
  }
  if ((in_model & (1u << kGaussMarkov)) && (in_model & (1u << kSinusoid)))
    SearchBothAgain(s, in_model, best, best_stat);
  SetIntervals(curve, &best.m, phase_points, o.allan.confidence);
  return best;
}

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

}  // namespace mpcal::internal::noise_fit
