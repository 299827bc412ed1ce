// The model of an Allan curve and its fit (term_model.h): the columns of
// σ²(τ), the non-negative weighted least squares over every support set, the
// reweighting from the model's own variance, and each point's interval from
// the noise type that dominates it.
#include "noise/term_model.h"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include <Eigen/Dense>

#include "mpcal/noise.h"

namespace mpcal::internal::noise_fit {

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

double FilteredWhite(double phi, double tau0_s, double tau_s) {
  const double m = std::max(1.0, std::round(tau_s / tau0_s));
  const double pm = std::pow(phi, m);
  const double r = phi / (1.0 - phi * phi);
  return (1.0 - r * (4.0 * (1.0 - pm) - (1.0 - pm * pm)) / m) / tau_s;
}

TermMask IeeeTerms(const Model& m) {
  return m.lowpass_phi > 0.0 ? kIeeeTerms & ~(1u << kQuantIndex) : kIeeeTerms;
}

Fit FitNonNegative(const std::vector<AllanPoint>& curve,
                   const std::vector<double>& weight,
                   const Model& shape,
                   TermMask allowed,
                   TermMask signed_terms,
                   TermMask required) {
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

void SetIntervals(std::vector<AllanPoint>& curve,
                  const Model* m,
                  double phase_points,
                  double confidence) {
  const double lo_p = 0.5 * (1.0 - confidence);
  for (AllanPoint& p : curve) {
    p.dominant = m ? Dominant(*m, p.tau_s) : NoiseTerm::kWhiteNoise;
    const double edf =
        std::min(OverlappingAllanEdf(phase_points, static_cast<double>(p.m), p.dominant),
                 static_cast<double>(p.terms));
    // The interval follows from the EDF alone (the confidence is the same in
    // every call on one curve): a point whose EDF the new model leaves as it
    // was keeps its interval: the fit sets the intervals at every step, and
    // the χ² quantiles are what that costs.
    if (edf == p.edf && p.adev_hi > 0.0) continue;
    p.edf = edf;
    p.adev_lo = std::sqrt(p.avar * p.edf / ChiSquareQuantile(1.0 - lo_p, p.edf));
    p.adev_hi = std::sqrt(p.avar * p.edf / ChiSquareQuantile(lo_p, p.edf));
  }
}

std::vector<double> ModelWeights(const std::vector<AllanPoint>& curve, const Model& m) {
  std::vector<double> weight(curve.size());
  for (std::size_t j = 0; j < curve.size(); ++j) {
    const double model = m.Avar(curve[j].tau_s);
    weight[j] = curve[j].edf / (2.0 * model * model);
  }
  return weight;
}

Fit FitTerms(std::vector<AllanPoint>& curve,
             TermMask allowed,
             double phase_points,
             const NoiseOptions& o,
             TermMask signed_terms,
             const Model& shape,
             TermMask required,
             const Model* start) {
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

LineMinimum GoldenSection(const std::function<double(double)>& cost,
                          double a,
                          double b,
                          int iterations) {
  constexpr double kGolden = 0.6180339887498949;  // (√5 − 1) / 2
  double x1 = b - kGolden * (b - a), x2 = a + kGolden * (b - a);
  double f1 = cost(x1), f2 = cost(x2);
  for (int it = 0; it < iterations; ++it) {
    if (f1 < f2) {
      b = x2, x2 = x1, f2 = f1;
      x1 = b - kGolden * (b - a);
      f1 = cost(x1);
    } else {
      a = x1, x1 = x2, f1 = f2;
      x2 = a + kGolden * (b - a);
      f2 = cost(x2);
    }
  }
  return f1 < f2 ? LineMinimum{x1, f1} : LineMinimum{x2, f2};
}

}  // namespace mpcal::internal::noise_fit
