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

double ResidualSigma(const ErrorModel& model, const Eigen::Vector3d& mean_mps2,
                     const Eigen::Vector3d& noise_mps2, std::size_t samples) {
  // ∇_Y |a| = (a/|a|)ᵀ T diag(1/(1+s)).
  const Eigen::Vector3d a = model.Correct(mean_mps2);
  const Eigen::RowVector3d gradient =
      (a.normalized().transpose() * model.NonOrthogonality())
          .cwiseQuotient((Eigen::Vector3d::Ones() + model.scale_factor_error).transpose());
  const double variance =
      gradient.cwiseProduct(noise_mps2.transpose()).squaredNorm() /
      static_cast<double>(std::max<std::size_t>(samples, 1));
  return std::sqrt(variance);
}

double PositionScatterVariance(const std::vector<double>& residuals_mps2,
                               const std::vector<double>& sigmas_mps2, int parameters) {
  // Median of the χ² distribution with one degree of freedom.
  constexpr double kChiSquare1Median = 0.454936;
  const std::size_t count = residuals_mps2.size();
  // The median of a few residuals cannot tell a scatter from chance (a
  // white-noise session of 15 positions once passed the test below); with
  // little redundancy the variance factor is the only safeguard.
  constexpr std::size_t kMinRedundancy = 10;
  if (count < static_cast<std::size_t>(parameters) + kMinRedundancy) return 0.0;
  const double target = kChiSquare1Median * static_cast<double>(count - parameters) /
                        static_cast<double>(count);
  auto median_ratio = [&](double tau2) {
    std::vector<double> q(count);
    for (std::size_t k = 0; k < count; ++k) {
      q[k] = residuals_mps2[k] * residuals_mps2[k] /
             (sigmas_mps2[k] * sigmas_mps2[k] + tau2);
    }
    std::nth_element(q.begin(), q.begin() + count / 2, q.end());
    return q[count / 2];
  };
  // Only on clear evidence. The sample median of K χ²₁ values scatters by
  // about 2.33/√K of itself, with a heavier right tail than a Gaussian: over
  // 200 white-noise sessions of 15-31 positions (mpcal_accuracy_bench) the
  // ratio below reached 3.4, while the real Xsens recording gives 17.8. Ten
  // such spreads (4.8 for K = 38, 5.4 for K = 28) separate the two.
  constexpr double kEvidenceSigmas = 10.0;
  const double evidence_ratio =
      1.0 + kEvidenceSigmas * 2.33 / std::sqrt(static_cast<double>(count));
  if (median_ratio(0.0) <= evidence_ratio * target) return 0.0;
  // The ratio falls monotonically with τ²: bisect between 0 and the largest
  // squared residual over the target, which brings every r²/(σ² + τ²), and
  // so their median, below the target.
  double lo = 0.0;
  double hi = 0.0;
  for (double r : residuals_mps2) hi = std::max(hi, r * r / target);
  for (int i = 0; i < 100 && hi - lo > 1e-12 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (median_ratio(mid) > target ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace mpcal::internal
