// Upper tails of the χ² and F distributions (distributions.h).
#include "mpcal/distributions.h"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

namespace mpcal {
namespace {

// The continued fraction of the incomplete beta function (Lentz's method),
// converging for x < (a + 1)/(a + b + 2).
double BetaContinuedFraction(double a, double b, double x) {
  constexpr double kTiny = 1e-300;
  double c = 1.0;
  double d = 1.0 - (a + b) * x / (a + 1.0);
  d = 1.0 / (std::abs(d) < kTiny ? kTiny : d);
  double h = d;
  for (int m = 1; m <= 300; ++m) {
    for (int half = 0; half < 2; ++half) {
      const double numerator =
          half == 0 ? m * (b - m) * x / ((a + 2.0 * m - 1.0) * (a + 2.0 * m))
                    : -(a + m) * (a + b + m) * x / ((a + 2.0 * m) * (a + 2.0 * m + 1.0));
      d = 1.0 + numerator * d;
      d = 1.0 / (std::abs(d) < kTiny ? kTiny : d);
      c = 1.0 + numerator / c;
      if (std::abs(c) < kTiny) c = kTiny;
      h *= d * c;
      if (half == 1 && std::abs(d * c - 1.0) < 1e-15) return h;
    }
  }
  return h;
}

// The regularised incomplete beta function I_x(a, b).
double RegularisedBeta(double x, double a, double b) {
  if (x <= 0.0) return 0.0;
  if (x >= 1.0) return 1.0;
  const double front = std::exp(std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) +
                                a * std::log(x) + b * std::log1p(-x));
  if (x < (a + 1.0) / (a + b + 2.0)) return front * BetaContinuedFraction(a, b, x) / a;
  return 1.0 - front * BetaContinuedFraction(b, a, 1.0 - x) / b;
}

}  // namespace

double FUpperTail(double f, int d1, int d2) {
  if (!(f > 0.0)) return 1.0;
  return RegularisedBeta(d2 / (d2 + d1 * f), 0.5 * d2, 0.5 * d1);
}

double ChiSquareUpperTail(double chi2, int dof) {
  assert(dof >= 1 && chi2 >= 0.0);
  // Regularised upper incomplete gamma Q(dof/2, chi2/2) in closed form: a
  // finite Poisson sum for even dof, erfc plus half-integer terms for odd dof.
  const double y = chi2 / 2.0;
  const double e = std::exp(-y);
  if (dof % 2 == 0) {
    double term = e;  // y^0/0! e^{-y}
    double sum = term;
    for (int j = 1; j < dof / 2; ++j) {
      term *= y / j;
      sum += term;
    }
    return std::min(1.0, sum);
  }
  double sum = std::erfc(std::sqrt(y));
  if (dof >= 3) {
    // y^{j-1/2} / Γ(j+1/2), j = 1: √y / Γ(3/2) = 2√(y/π).
    double term = e * 2.0 * std::sqrt(y / std::numbers::pi);
    sum += term;
    for (int j = 2; j <= (dof - 1) / 2; ++j) {
      term *= y / (j - 0.5);
      sum += term;
    }
  }
  return std::min(1.0, sum);
}

}  // namespace mpcal
