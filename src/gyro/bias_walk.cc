#include "bias_walk.h"

#include <algorithm>
#include <vector>

namespace mpcal::internal {

double BridgeIntegralVariance(double pin_a_s, double pin_b_s, double s0_s, double s1_s) {
  const double span = pin_b_s - pin_a_s;
  if (!(span > 0.0)) return 0.0;
  // Cov(B(s), B(u)) = min(s, u) − s·u/span (times from pin a), so
  // Var ∫_a^b B = a·L² + L³/3 − ((b² − a²)/2)²/span with L = b − a.
  const double a = std::clamp(s0_s - pin_a_s, 0.0, span);
  const double b = std::clamp(s1_s - pin_a_s, 0.0, span);
  const double l = b - a;
  const double first_moment = 0.5 * (b * b - a * a);
  return std::max(0.0, a * l * l + l * l * l / 3.0 - first_moment * first_moment / span);
}

double EstimateBiasWalk(const TurnProblem& problem,
                        std::span<const StaticInterval> intervals,
                        const RecordingView& recording,
                        const Calibration& accel) {
  const std::size_t n = std::min(intervals.size(), problem.bias_raw.size());
  if (n < 3) return 0.0;
  // The rest bias that is interpolated: without G f when the model has it.
  std::vector<Eigen::Vector3d> bias;
  for (std::size_t k = 0; k < n; ++k) {
    Eigen::Vector3d b = problem.bias_raw[k].bias_radps;
    if (problem.g_sensitivity_used) {
      b -= problem.g_sensitivity_raw_per_mps2 * accel.Correct(intervals[k].mean);
    }
    bias.push_back(b);
  }
  auto length_s = [&](std::size_t k) {
    return recording.time_s[intervals[k].end - 1] - recording.time_s[intervals[k].begin];
  };
  // The samples in each position's mean: the gyroscope's own when it was
  // recorded apart.
  auto count = [&](std::size_t k) {
    const std::size_t samples = k < problem.bias_samples.size()
                                    ? problem.bias_samples[k]
                                    : intervals[k].end - intervals[k].begin;
    return static_cast<double>(std::max<std::size_t>(samples, 1));
  };
  // Drift per second, the ratio estimator (least squares with weights 1/Δt).
  Eigen::Vector3d change = Eigen::Vector3d::Zero();
  double elapsed_s = 0.0;
  for (std::size_t k = 0; k + 1 < n; ++k) {
    change += bias[k + 1] - bias[k];
    elapsed_s += problem.bias_raw[k + 1].t_s - problem.bias_raw[k].t_s;
  }
  if (!(elapsed_s > 0.0)) return 0.0;
  const Eigen::Vector3d drift = change / elapsed_s;
  const double var_sample = problem.noise_std_raw * problem.noise_std_raw;
  double squares = 0.0;  // Σ |change − drift Δt|², all three axes
  double white = 0.0;    // its expectation from the means' white noise
  double walk_s = 0.0;   // its expectation per unit walk density², per axis
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const double dt_s = problem.bias_raw[k + 1].t_s - problem.bias_raw[k].t_s;
    squares += (bias[k + 1] - bias[k] - drift * dt_s).squaredNorm();
    white += 3.0 * var_sample * (1.0 / count(k) + 1.0 / count(k + 1));
    walk_s += std::max(0.0, dt_s - (length_s(k) + length_s(k + 1)) / 6.0);
  }
  // The drift takes one change per axis out of the n − 1.
  const double changes = static_cast<double>(n - 1);
  squares *= changes / (changes - 1.0);
  if (!(walk_s > 0.0)) return 0.0;
  return std::max(0.0, (squares - white) / (3.0 * walk_s));
}

void AddBiasWalk(double walk_raw2_per_s, TurnProblem* problem) {
  if (!(walk_raw2_per_s > 0.0)) return;
  for (TurnData& t : problem->turns) {
    const std::size_t k = t.from_position;
    if (k + 1 >= problem->bias_raw.size()) continue;
    t.gyro_variance_raw2s2 +=
        walk_raw2_per_s *
        BridgeIntegralVariance(
            problem->bias_raw[k].t_s, problem->bias_raw[k + 1].t_s, t.start_s, t.end_s);
  }
}

}  // namespace mpcal::internal
