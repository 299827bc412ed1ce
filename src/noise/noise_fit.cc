// The noise terms of one axis from its Allan curve: a non-negative weighted
// least-squares fit of the sum of the IEEE 952 terms in the variance domain,
// each term kept only where it dominates, with the confidence intervals of
// every point set from the noise type the fit says dominates there.
#include "noise/noise_fit.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "mpcal/noise.h"
#include "noise/extra_terms.h"
#include "noise/lowpass_fit.h"
#include "noise/term_measure.h"
#include "noise/term_model.h"

namespace mpcal {

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
  for (int t = 0; t < internal::noise_fit::kTerms; ++t)
    sum += fit_avar_coefficients[t] * internal::noise_fit::Basis(t, tau_s);
  sum += GaussMarkovAvar(fit_gauss_markov.sigma2, fit_gauss_markov.tau_c_s, tau_s);
  sum += SinusoidAvar(fit_sinusoid.amplitude2, fit_sinusoid.period_s, tau_s);
  return sum;
}

namespace internal {

using namespace noise_fit;

namespace {

// One fit with every IEEE term (non-negative: those the curve does not
// support come out zero or small), then the Gauss-Markov process and the
// sinusoid where the criterion admits them; each term is reported only
// where it dominates. Refitting without the terms not seen would push
// their variance into their neighbours (a bias instability under the
// white noise and random walk would inflate both). No fit at all leaves the
// curve's intervals those of no model.
Fit FitWholeCurve(std::vector<AllanPoint>& curve,
                  double phase_points,
                  const NoiseOptions& o) {
  Fit fit = FitTerms(curve, kIeeeTerms, phase_points, o, 0);
  if (std::isfinite(fit.cost))
    fit = AddExtraTerms(curve, fit, 0, curve.front().tau_s, phase_points, o);
  if (!std::isfinite(fit.cost)) {
    fit = Fit{};
    SetIntervals(curve, nullptr, phase_points, o.allan.confidence);
  }
  return fit;
}

// The fit kept for an axis: from the cluster time `from` on (0: the whole
// curve), its check, and the terms allowed a negative coefficient.
struct CurveFit {
  std::size_t from = 0;
  Fit fit;
  ModelCheck check;
  TermMask signed_terms = 0;
};

// What a fit from the k-th cluster time on is searched with.
struct ShortEndCut {
  const std::vector<AllanPoint>& curve;  // the whole curve
  std::size_t k;
  std::vector<AllanPoint> kept;  // the curve from its k-th cluster time
  double first_tau_s;            // the whole curve's first cluster time
  double tau0_s;                 // the sample period
  double phase_points;
  const NoiseOptions& o;
};

// The filter's coefficient φ searched with the terms of `seed`, the extra
// terms added after; when that adds one (a bump rising just beyond the
// roll-off bends φ), φ searched again with it.
Fit FilterFrom(ShortEndCut& s, const Fit& seed) {
  Fit f = SearchLowpass(s.kept, seed, s.tau0_s, s.phase_points, s.o);
  if (!std::isfinite(f.cost)) return f;
  f = AddExtraTerms(s.kept, f, 0, s.first_tau_s, s.phase_points, s.o);
  if (f.m.c[kGaussMarkov] > 0.0 || f.m.c[kSinusoid] > 0.0) {
    const Fit again = SearchLowpass(s.kept, f, s.tau0_s, s.phase_points, s.o);
    if (std::isfinite(again.cost)) f = again;
  }
  return f;
}

// `f` fitted from the k-th cluster time, when it is kept: it passes the
// check, the short end cut off lies below its positive terms (the white
// noise line, unfiltered: a roll-off, not an excess), and the first cluster
// time kept lies inside the curve's interval (what is left of the roll-off
// there would pull N down, so the cut goes on).
std::optional<CurveFit> Kept(const ShortEndCut& s, const Fit& f, TermMask signs) {
  if (!std::isfinite(f.cost)) return std::nullopt;
  ModelCheck check = CheckModel(s.kept, f.m, s.o);
  Model positive = f.m;
  positive.lowpass_phi = 0.0;
  for (double& c_t : positive.c) c_t = std::max(c_t, 0.0);
  bool below = true;
  for (std::size_t j = 0; j < s.k; ++j) {
    below = below && s.curve[j].adev < std::sqrt(positive.Avar(s.curve[j].tau_s));
  }
  const bool starts_inside =
      check.disagree.empty() || check.disagree.front().lo_s > s.kept.front().tau_s;
  if (!check.fits || !below || !starts_inside) return std::nullopt;
  return CurveFit{s.k, f, std::move(check), signs};
}

// The fit from the k-th cluster time on, when one is kept. Beyond a few
// correlation times of a first-order low-pass the white noise it filtered
// has σ²(τ) = N²/τ − D/τ² up to terms in φ^m (its output is an AR(1)
// sequence, whose sums have a closed-form variance): the quantisation's
// basis with a negative coefficient, allowed here (never reported: a term
// is measured only where it is positive). That remnant is exact with the
// filter's own σ²(τ) for the white noise (FilteredWhite, φ fitted), which
// ties D to N² and leaves N less entangled with a bump rising just beyond:
// tried first, from the IEEE fit and then from the asymptotic one; the
// signed term serves a roll-off that is not first-order.
std::optional<CurveFit> FitFrom(ShortEndCut& s) {
  const TermMask quant = 1u << kQuantIndex;
  const Fit ieee = FitTerms(s.kept, kIeeeTerms, s.phase_points, s.o, quant);
  if (!std::isfinite(ieee.cost)) return std::nullopt;
  const Fit asymptotic =
      AddExtraTerms(s.kept, ieee, quant, s.first_tau_s, s.phase_points, s.o);
  if (auto c = Kept(s, FilterFrom(s, ieee), 0)) return c;
  if (std::isfinite(asymptotic.cost)) {
    if (auto c = Kept(s, FilterFrom(s, asymptotic), 0)) return c;
  }
  return Kept(s, asymptotic, quant);
}

// A model that misses the curve: when its short-τ end rolls off below the
// model like a low-pass filter's, the fit starts further out, at the first
// cluster time from which the model fits and that lies inside the curve's
// interval (at most half the curve left out). A short end that rolls off
// (flatter than −½ at the first cluster time) under a model with an extra
// term is tried cut too, even where that model passes the check: the term
// may stand in for a filter (a bump of τc near the filter's, whose output is
// itself a Gauss-Markov process) and take N with it. The cut is kept when
// it fits.
CurveFit FitCurve(std::vector<AllanPoint>& curve,
                  double phase_points,
                  const NoiseOptions& o) {
  CurveFit whole;
  whole.fit = FitWholeCurve(curve, phase_points, o);
  whole.check = CheckModel(curve, whole.fit.m, o);
  const bool rolls_off =
      (whole.fit.m.c[kGaussMarkov] > 0.0 || whole.fit.m.c[kSinusoid] > 0.0) &&
      ShortEndRollsOff(curve, 1, o.allan.confidence);
  if (whole.check.fits && !rolls_off) return whole;
  const double first_tau_s = curve.front().tau_s;
  const double tau0_s = first_tau_s / static_cast<double>(curve.front().m);
  for (std::size_t k = 1;
       k <= curve.size() / 2 && ShortEndRollsOff(curve, k, o.allan.confidence);
       ++k) {
    ShortEndCut s{curve,
                  k,
                  std::vector<AllanPoint>(curve.begin() + static_cast<std::ptrdiff_t>(k),
                                          curve.end()),
                  first_tau_s,
                  tau0_s,
                  phase_points,
                  o};
    if (std::optional<CurveFit> cut = FitFrom(s)) {
      SetIntervals(curve, &cut->fit.m, phase_points, o.allan.confidence);
      return std::move(*cut);
    }
  }
  return whole;
}

// A term whose region meets a stretch where the model misses the curve is
// not presented as measured.
void WithdrawMisfits(const ModelCheck& check, const NoiseOptions& o, AxisNoise& out) {
  if (check.fits) return;
  const auto meets_misfit = [&check](double lo_s, double hi_s) {
    for (const TauRange& r : check.disagree) {
      if (r.lo_s <= hi_s && r.hi_s >= lo_s) return true;
    }
    return false;
  };
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

}  // namespace

// The fit, the terms read where the curve supports them, those the model
// misses withdrawn, and bounds for the rest.
AxisNoise AnalyseAxis(std::vector<AllanPoint> curve,
                      double phase_points,
                      const NoiseOptions& o) {
  AxisNoise out;
  out.gauss_markov.modelled = o.model_gauss_markov;
  out.sinusoid.modelled = o.model_sinusoid;
  const double tau0_s = curve.front().tau_s / static_cast<double>(curve.front().m);
  CurveFit fit = FitCurve(curve, phase_points, o);
  fit.check.excluded = static_cast<int>(fit.from);
  const Model& m = fit.fit.m;
  for (int t = 0; t < kTerms; ++t) out.fit_avar_coefficients[t] = m.c[t];
  if (m.c[kGaussMarkov] > 0.0) out.fit_gauss_markov = {m.c[kGaussMarkov], m.tau_c_s};
  if (m.c[kSinusoid] > 0.0) out.fit_sinusoid = {m.c[kSinusoid], m.period_s};

  const std::vector<AllanPoint> kept(
      curve.begin() + static_cast<std::ptrdiff_t>(fit.from), curve.end());
  MeasureTerms(kept, fit.fit, o, out);
  MeasureExtraTerms(kept, fit.fit, fit.signed_terms, o, out);
  WithdrawMisfits(fit.check, o, out);
  BoundTerms(kept, fit.fit, (phase_points - 1.0) * tau0_s, o, out);
  out.check = std::move(fit.check);
  out.curve = std::move(curve);
  return out;
}

}  // namespace internal
}  // namespace mpcal
