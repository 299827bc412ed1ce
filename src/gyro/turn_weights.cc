#include "turn_weights.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "bias_walk.h"

namespace mpcal::internal {
namespace {

// The turns' gyroscope variance with the white noise, where the scatter at
// rest is larger (a trembling hand): the integration over a turn follows the
// tremor, so only the white noise is error.
void UseWhiteNoise(double white_std_raw, TurnProblem* problem) {
  const double scatter = problem->noise_std_raw;
  if (!(white_std_raw > 0.0) || !(white_std_raw < scatter)) return;
  const double ratio = (white_std_raw * white_std_raw) / (scatter * scatter);
  for (TurnData& t : problem->turns) t.gyro_variance_raw2s2 *= ratio;
}

// Per tangent component, the squared angle between two unit directions.
double HalfSquaredAngle(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return 0.5 * (a - b).squaredNorm();
}

}  // namespace

double WhiteNoiseStd(const RecordingView& recording,
                     std::span<const StaticInterval> intervals) {
  // On the gyroscope's own samples (the rows' means of a gyroscope recorded
  // apart share samples with their neighbours: their second differences
  // would not be white noise's).
  const GyroSamples s = SamplesOf(recording);
  std::vector<double> stds;
  for (const StaticInterval& in : intervals) {
    const auto [first, last] =
        SamplesWithin(s, recording.time_s[in.begin], recording.time_s[in.end - 1]);
    if (last < first + 3) continue;
    double sum = 0.0;
    for (std::size_t i = first + 1; i + 1 < last; ++i) {
      sum += (s.rate[i + 1] - 2.0 * s.rate[i] + s.rate[i - 1]).squaredNorm();
    }
    stds.push_back(std::sqrt(sum / (18.0 * static_cast<double>(last - first - 2))));
  }
  if (stds.empty()) return 0.0;
  std::nth_element(stds.begin(), stds.begin() + stds.size() / 2, stds.end());
  return stds[stds.size() / 2];
}

GyroDirections ChooseDirections(double white_std_raw,
                                double radps_per_unit,
                                TurnProblem* problem) {
  GyroDirections out;
  if (problem->turns.empty() || !(radps_per_unit > 0.0)) return out;
  const double per_second_raw2s2 =
      white_std_raw * white_std_raw * problem->sample_period_s / 3.0;
  double difference_rad2 = 0.0;
  double carry_rad2 = 0.0;
  for (const TurnData& t : problem->turns) {
    difference_rad2 += HalfSquaredAngle(t.from.carried, t.from.still) +
                       HalfSquaredAngle(t.to.carried, t.to.still);
    carry_rad2 += per_second_raw2s2 * radps_per_unit * radps_per_unit *
                  (t.from.window_s + t.to.window_s);
  }
  const double edges = 2.0 * static_cast<double>(problem->turns.size());
  const double sway_rad2 = std::max(0.0, (difference_rad2 - carry_rad2) / edges);
  out.sway_rad = std::sqrt(sway_rad2);
  out.carry_noise_rad = std::sqrt(carry_rad2 / edges);
  out.carried = sway_rad2 > carry_rad2 / edges;
  for (TurnData& t : problem->turns) {
    if (out.carried) {
      t.gyro_variance_raw2s2 += per_second_raw2s2 * (t.from.window_s + t.to.window_s);
    } else {
      t.direction_variance_rad2 += 2.0 * sway_rad2;
      UseDirections(t.from.still, t.to.still, &t);
    }
  }
  return out;
}

GyroDirections WeighTurns(const RecordingView& recording,
                          std::span<const StaticInterval> intervals,
                          const Calibration& accel,
                          double radps_per_unit,
                          TurnProblem* problem) {
  const double white =
      std::min(WhiteNoiseStd(recording, intervals), problem->noise_std_raw);
  UseWhiteNoise(white, problem);
  // The bias's random walk between the positions, which the interpolation
  // across each turn leaves in it: in the weights, so that a gyroscope whose
  // bias wanders weights its long turns between far-apart positions less.
  AddBiasWalk(EstimateBiasWalk(*problem, intervals, recording, accel), problem);
  return ChooseDirections(white, radps_per_unit, problem);
}

}  // namespace mpcal::internal
