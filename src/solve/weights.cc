#include "weights.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace mpcal::internal {

std::vector<Eigen::Vector3d> UsableNoise(std::span<const PositionObservation> positions) {
  // The median over positions is the typical noise of each axis; a position
  // far below it is quantisation, not a better sensor.
  Eigen::Vector3d typical = Eigen::Vector3d::Zero();
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<double> s;
    s.reserve(positions.size());
    for (const auto& p : positions) s.push_back(p.sample_std_mps2[axis]);
    std::nth_element(s.begin(), s.begin() + s.size() / 2, s.end());
    typical[axis] = s.empty() ? 0.0 : s[s.size() / 2];
  }
  // With no noise at all (synthetic means), any common level gives the same
  // estimate; the a-posteriori variance factor carries the scale.
  const double floor_mps2 = std::max(1e-3 * typical.maxCoeff(), 1e-9);
  std::vector<Eigen::Vector3d> noise;
  noise.reserve(positions.size());
  for (const auto& p : positions) {
    Eigen::Vector3d n;
    for (int axis = 0; axis < 3; ++axis) {
      n[axis] = std::max({p.sample_std_mps2[axis], 0.5 * typical[axis], floor_mps2});
    }
    noise.push_back(n);
  }
  return noise;
}

double ResidualSigma(const ErrorModel& model,
                     const Eigen::Vector3d& mean_mps2,
                     const Eigen::Vector3d& noise_mps2,
                     std::size_t samples) {
  // ∇_Y |a| = (a/|a|)ᵀ T diag(1/(1+s)).
  const Eigen::Vector3d a = model.Correct(mean_mps2);
  const Eigen::RowVector3d gradient =
      (a.normalized().transpose() * model.NonOrthogonality())
          .cwiseQuotient(
              (Eigen::Vector3d::Ones() + model.scale_factor_error).transpose());
  const double variance = gradient.cwiseProduct(noise_mps2.transpose()).squaredNorm() /
                          static_cast<double>(std::max<std::size_t>(samples, 1));
  return std::sqrt(variance);
}

double ChiSquare1MedianQuantile(std::size_t count, double alpha) {
  // P(median > x) = P(fewer than rank + 1 of the count values are <= x)
  // = Σ_{i <= rank} C(count, i) F^i (1 − F)^(count − i), F the χ²₁ CDF.
  const std::size_t rank = count / 2;
  auto tail = [&](double x) {
    const double f = std::erf(std::sqrt(x / 2.0));
    double sum = 0.0;
    for (std::size_t i = 0; i <= rank; ++i) {
      const double log_term = std::lgamma(count + 1.0) - std::lgamma(i + 1.0) -
                              std::lgamma(count - i + 1.0) + i * std::log(f) +
                              (count - i) * std::log1p(-f);
      sum += std::exp(log_term);
    }
    return sum;
  };
  double lo = 0.0;
  double hi = 50.0;
  for (int i = 0; i < 200 && hi - lo > 1e-12; ++i) {
    const double mid = 0.5 * (lo + hi);
    (tail(mid) > alpha ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double PositionScatterVariance(const std::vector<double>& residuals_mps2,
                               const std::vector<double>& sigmas_mps2,
                               const std::vector<double>& leverages) {
  const std::size_t count = residuals_mps2.size();
  double parameters = 0.0;
  for (double h : leverages) parameters += h;
  if (static_cast<double>(count) - parameters < kMinScatterRedundancy - 0.5) return 0.0;
  auto median_ratio = [&](double tau2) {
    std::vector<double> q(count);
    for (std::size_t k = 0; k < count; ++k) {
      const double h = std::clamp(leverages[k], 0.0, 0.999);
      q[k] = residuals_mps2[k] * residuals_mps2[k] /
             ((sigmas_mps2[k] * sigmas_mps2[k] + tau2) * (1.0 - h));
    }
    std::nth_element(q.begin(), q.begin() + count / 2, q.end());
    return q[count / 2];
  };
  if (median_ratio(0.0) <= ChiSquare1MedianQuantile(count, kScatterSignificance))
    return 0.0;
  // Both ratios fall monotonically with τ²: bisect between 0 and the
  // largest squared residual over the target, which brings every ratio, and
  // so their median and mean, below the target.
  auto solve = [&](auto ratio, double target) {
    double lo = 0.0;
    double hi = 0.0;
    for (std::size_t k = 0; k < count; ++k) {
      const double h = std::clamp(leverages[k], 0.0, 0.999);
      hi = std::max(hi, residuals_mps2[k] * residuals_mps2[k] / (target * (1.0 - h)));
    }
    if (ratio(0.0) <= target) return 0.0;
    for (int i = 0; i < 100 && hi - lo > 1e-12 * hi; ++i) {
      const double mid = 0.5 * (lo + hi);
      (ratio(mid) > target ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
  };
  auto mean_ratio = [&](double tau2) {
    double sum = 0.0;
    for (std::size_t k = 0; k < count; ++k) {
      const double h = std::clamp(leverages[k], 0.0, 0.999);
      sum += residuals_mps2[k] * residuals_mps2[k] /
             ((sigmas_mps2[k] * sigmas_mps2[k] + tau2) * (1.0 - h));
    }
    return sum / static_cast<double>(count);
  };
  // The smaller of the robust estimate (the median matched to χ²₁'s) and the
  // moment estimate (the mean matched to 1): the median keeps a few bumped
  // positions from inflating τ², the mean keeps a median that is high by
  // chance (white noise that just passed the test) from doing so.
  return std::min(solve(median_ratio, kChiSquare1Median), solve(mean_ratio, 1.0));
}

}  // namespace mpcal::internal
