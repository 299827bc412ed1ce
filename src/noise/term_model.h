// Private to src/noise/: the model of an Allan curve that the term fit
// (noise_fit.cc AnalyseAxis, term_measure.cc, extra_terms.cc, lowpass_fit.cc)
// shares: the columns of σ²(τ) (the IEEE 952 terms, a Gauss-Markov process,
// a sinusoid, white noise through a low-pass filter), the non-negative
// weighted least-squares fit of their coefficients, and the noise type that
// sets each point's confidence interval.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <limits>
#include <vector>

#include "mpcal/noise.h"

namespace mpcal::internal::noise_fit {

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

/// σ²(τ) per unit coefficient of each term (IEEE 952 Table C.2).
double Basis(int term, double tau_s);

/// σ²(τ) per unit N² of white noise through the first-order low-pass
/// y_n = φ y_{n−1} + (1 − φ) x_n sampled every τ0 (unit gain at zero
/// frequency): the output is an AR(1) sequence, and the variance of a sum of
/// m of its samples gives, exactly at τ = m τ0,
///   σ²(τ) = (1/τ) [1 − φ/(1 − φ²) · (4(1 − φ^m) − (1 − φ^{2m})) / m],
/// (1 − φ)²/((1 + φ) τ0) at m = 1, → 1/τ − 3φ τ0/((1 − φ²) τ²) for large m.
double FilteredWhite(double phi, double tau0_s, double tau_s);

/// The fitted model: the coefficients of every column, the correlation time
/// and period that make the last two linear, and the low-pass filter the
/// white noise went through (φ = 0: none).
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

/// The IEEE terms a model fits: all five, or with the low-pass filter in
/// the white noise's column all but the quantisation, whose 1/τ² at the
/// short end trades against φ and N (a record quantised after its filter is
/// left to the fit with the signed remnant, see AnalyseAxis).
TermMask IeeeTerms(const Model& m);

/// A fitted model, the variance of each coefficient and the weighted cost
/// (infinite: no support set fits).
struct Fit {
  Model m;
  Coefficients variance{};  // of each coefficient
  double cost = std::numeric_limits<double>::infinity();
};

/// Non-negative least squares over the columns in `allowed` that include
/// all of `required`: the optimum lies on some support set where the
/// unconstrained optimum is positive, so every such subset is tried (exact,
/// and at most 127 tiny solves). `signed_terms`: those that may come out
/// negative (the roll-off of a low-pass filter beyond its short-τ end, see
/// AnalyseAxis). The model's τc and period are kept; its coefficients set.
Fit FitNonNegative(const std::vector<AllanPoint>& curve,
                   const std::vector<double>& weight,
                   const Model& shape,
                   TermMask allowed,
                   TermMask signed_terms = 0,
                   TermMask required = 0);

/// The noise type of the EDF at τ: that of the largest part of the model. A
/// Gauss-Markov process is a random walk below its correlation time and a
/// white noise above; a sinusoid is taken as white.
NoiseTerm Dominant(const Model& m, double tau_s);

/// EDF and interval of every point for the dominant term of `m` (white noise
/// before any fit); on one curve, always with the same `confidence` (a point
/// whose EDF is unchanged keeps the interval it has).
void SetIntervals(std::vector<AllanPoint>& curve,
                  const Model* m,
                  double phase_points,
                  double confidence);

/// Weights 1 / var(σ̂²) = edf / (2 model²), from the model's variance rather
/// than the data's (weights from the data would pull the fit towards the
/// points that came out low), with the curve's EDF as SetIntervals left it.
std::vector<double> ModelWeights(const std::vector<AllanPoint>& curve, const Model& m);

/// The reweighted fit over the columns `allowed` (those in `required`
/// always), at the τc and period of `shape`; weights from `start` when given
/// (else from the data, then from the model).
Fit FitTerms(std::vector<AllanPoint>& curve,
             TermMask allowed,
             double phase_points,
             const NoiseOptions& o,
             TermMask signed_terms = 0,
             const Model& shape = Model{},
             TermMask required = 0,
             const Model* start = nullptr);

/// Points where column t carries at least `dominance` of the fitted variance.
std::vector<std::size_t> DominatedPoints(const std::vector<AllanPoint>& curve,
                                         const Model& m,
                                         int t,
                                         double dominance);

/// The least of `cost` on [a, b] by golden-section search over `iterations`
/// steps: where, and the cost there (the better of the last two probes; an
/// infinite cost when no probe fitted). For the one-dimensional shapes of
/// the fit: a correlation time, a period, a filter's coefficient.
struct LineMinimum {
  double at = 0.0;
  double cost = std::numeric_limits<double>::infinity();
};
LineMinimum GoldenSection(const std::function<double(double)>& cost,
                          double a,
                          double b,
                          int iterations);

}  // namespace mpcal::internal::noise_fit
