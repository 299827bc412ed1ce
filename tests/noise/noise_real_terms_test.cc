// The terms real sensors add to the IEEE five: the closed-form Allan
// variances of a first-order Gauss-Markov process and of a sinusoid, held
// against computations that do not use them.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "mpcal/noise.h"

namespace mpcal {
namespace {

// The Allan variance of a process from its two-sided power spectral density
// S(f) (IEEE Std 952-1997 Annex C; white noise of S = N² gives N²/τ):
//   σ²(τ) = 4 ∫₀^∞ S(f) sin⁴(πfτ) / (πfτ)² df,
// integrated by the trapezoid rule in ln f over twelve decades around 1/τ.
template <typename Psd>
double AvarFromPsd(const Psd& psd, double tau_s) {
  const double lo = std::log(1e-6 / tau_s), hi = std::log(1e6 / tau_s);
  constexpr int kSteps = 400000;
  const double h = (hi - lo) / kSteps;
  double sum = 0.0;
  for (int i = 0; i <= kSteps; ++i) {
    const double f = std::exp(lo + i * h);
    const double x = std::numbers::pi * f * tau_s;
    const double s = std::sin(x);
    const double v = 4.0 * psd(f) * s * s * s * s / (x * x) * f;  // df = f d(ln f)
    sum += (i == 0 || i == kSteps) ? 0.5 * v : v;
  }
  return sum * h;
}

TEST(GaussMarkovAvar, MatchesItsSpectrum) {
  // x' = −x/τc + w of stationary variance σ²: two-sided PSD
  // 2σ²τc / (1 + (2πfτc)²) (its integral over all f is σ²).
  const double sigma2 = 2.5e-5, tau_c = 0.3;
  const auto psd = [&](double f) {
    const double w = 2.0 * std::numbers::pi * f * tau_c;
    return 2.0 * sigma2 * tau_c / (1.0 + w * w);
  };
  for (const double tau : {1e-4, 0.01, 0.1, 0.3, 0.57, 1.0, 3.0, 30.0, 1000.0}) {
    EXPECT_NEAR(GaussMarkovAvar(sigma2, tau_c, tau) / AvarFromPsd(psd, tau), 1.0, 1e-4)
        << tau;
  }
}

TEST(GaussMarkovAvar, RandomWalkBelowWhiteAboveBumpBetween) {
  const double sigma2 = 4.0, tau_c = 2.0;
  // τ ≪ τc: a random walk of K² = 2σ²/τc (σ²(τ) = K²τ/3); τ ≫ τc: a white
  // noise of N² = 2σ²τc.
  EXPECT_NEAR(GaussMarkovAvar(sigma2, tau_c, 1e-5) / (2.0 * sigma2 / tau_c * 1e-5 / 3.0),
              1.0,
              1e-5);
  EXPECT_NEAR(
      GaussMarkovAvar(sigma2, tau_c, 1e5) / (2.0 * sigma2 * tau_c / 1e5), 1.0, 1e-4);
  // Continuous across the switch to the series at τ = 10⁻³ τc.
  const double below = GaussMarkovAvar(sigma2, tau_c, 0.999999e-3 * tau_c);
  const double above = GaussMarkovAvar(sigma2, tau_c, 1.000001e-3 * tau_c);
  EXPECT_NEAR(above / below, 1.0, 1e-5);
  // The bump: its Allan deviation peaks at 0.62 σ near 1.89 τc.
  double best_tau = 0.0, best = 0.0;
  for (double tau = 0.1; tau < 20.0; tau *= 1.0005) {
    const double v = GaussMarkovAvar(sigma2, tau_c, tau);
    if (v > best) best = v, best_tau = tau;
  }
  EXPECT_NEAR(best_tau / tau_c, 1.89, 0.01);
  EXPECT_NEAR(std::sqrt(best / sigma2), 0.62, 0.005);
  EXPECT_EQ(GaussMarkovAvar(0.0, tau_c, 1.0), 0.0);
}

TEST(SinusoidAvar, MatchesTheSampledSinusoidOverPhases) {
  // Averages of A sin(2πt/P + φ) over adjacent windows of τ, fine-sampled,
  // their halved squared difference averaged over the phase φ.
  const double a = 0.003, period = 2.0;
  for (const double tau : {0.05, 0.37 * period, 1.0, 1.9, 2.0, 3.1, 10.0}) {
    constexpr int kPerWindow = 2000, kPhases = 64;
    double total = 0.0;
    for (int k = 0; k < kPhases; ++k) {
      const double phi = 2.0 * std::numbers::pi * k / kPhases;
      double first = 0.0, second = 0.0;
      for (int i = 0; i < kPerWindow; ++i) {
        const double t = (i + 0.5) * tau / kPerWindow;
        first += a * std::sin(2.0 * std::numbers::pi * t / period + phi);
        second += a * std::sin(2.0 * std::numbers::pi * (t + tau) / period + phi);
      }
      const double d = (second - first) / kPerWindow;
      total += 0.5 * d * d;
    }
    const double expected = total / kPhases;
    const double v = SinusoidAvar(a * a, period, tau);
    if (expected < 1e-12 * a * a) {
      EXPECT_LT(v, 1e-10 * a * a) << tau;  // a whole number of periods
    } else {
      EXPECT_NEAR(v / expected, 1.0, 1e-5) << tau;
    }
  }
}

TEST(FittedAvar, SumsTheIeeeTermsTheBumpAndTheSinusoid) {
  AxisNoise ax;
  ax.fit_avar_coefficients[static_cast<int>(NoiseTerm::kWhiteNoise)] = 1e-6;
  ax.fit_gauss_markov = {4e-6, 0.3};
  ax.fit_sinusoid = {9e-6, 2.0};
  const double tau = 0.6;
  EXPECT_DOUBLE_EQ(
      ax.FittedAvar(tau),
      1e-6 / tau + GaussMarkovAvar(4e-6, 0.3, tau) + SinusoidAvar(9e-6, 2.0, tau));
}

}  // namespace
}  // namespace mpcal
