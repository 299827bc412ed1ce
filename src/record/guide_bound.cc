// What the captured positions determine: the Cramér-Rao bound of the
// chosen model against the targets, the default targets, and the direction
// that helps the weakest parameter most (record_guide.h states the rules).
#include <algorithm>
#include <cmath>
#include <numbers>

#include "guide_steps.h"
#include "mpcal/coverage.h"
#include "mpcal/cramer_rao.h"
#include "mpcal/error.h"

namespace mpcal {
namespace {

bool Finite(double v) { return std::isfinite(v); }

BoundPosition AsBoundPosition(const Eigen::Vector3d& direction,
                              std::size_t samples,
                              const Eigen::Vector3d& noise) {
  BoundPosition p;
  p.direction = direction.normalized();
  p.noise_std_mps2 = noise;
  p.samples = samples;
  return p;
}

// The bound of `positions` (determined = false when singular).
GuideBound BoundOfPositions(std::span<const BoundPosition> positions,
                            const std::array<double, 3>& target,
                            const GuideOptions& options) {
  GuideBound b;
  b.target = target;
  b.std.fill(std::numeric_limits<double>::quiet_NaN());
  Eigen::Matrix<double, 9, 9> cov;
  try {
    cov = CramerRaoBound(ErrorModel{}, positions, options.gravity_mps2, options.model);
  } catch (const Error&) {
    return b;
  }
  b.determined = true;
  b.worst_ratio = 0.0;
  const int used = options.model == ModelKind::kBiasScale6 ? 6 : kNumModelParameters;
  for (int i = 0; i < kNumModelParameters; ++i) {
    b.std[static_cast<std::size_t>(i)] = std::sqrt(std::max(cov(i, i), 0.0));
    if (i >= used) continue;
    const double ratio =
        b.std[static_cast<std::size_t>(i)] / target[static_cast<std::size_t>(GroupOf(i))];
    if (!Finite(ratio)) {
      b.determined = false;
      b.worst_ratio = std::numeric_limits<double>::infinity();
      return b;
    }
    if (ratio > b.worst_ratio) {
      b.worst_ratio = ratio;
      b.worst = i;
    }
  }
  return b;
}

}  // namespace

ParameterGroup GroupOf(int index) {
  if (index < 3) return ParameterGroup::kBias;
  if (index < 6) return ParameterGroup::kScale;
  return ParameterGroup::kAngle;
}

std::string GuideOptions::Validate() const {
  if (std::string bad = detect.Validate(); !bad.empty()) return bad;
  if (!(target_bias_mps2 >= 0.0) || !Finite(target_bias_mps2))
    return "target_bias_mps2 must be >= 0";
  if (!(target_scale >= 0.0) || !Finite(target_scale)) return "target_scale must be >= 0";
  if (!(target_angle_rad >= 0.0) || !Finite(target_angle_rad))
    return "target_angle_rad must be >= 0";
  if (!(target_factor >= 1.0) || !Finite(target_factor))
    return "target_factor must be >= 1";
  if (!(near_deg > 0.0 && near_deg < 90.0)) return "near_deg must be in (0, 90)";
  if (!(gravity_mps2 > 0.0) || !Finite(gravity_mps2)) return "gravity_mps2 must be > 0";
  if (!(min_turn_deg > 0.0) || !Finite(min_turn_deg)) return "min_turn_deg must be > 0";
  return "";
}

GuideBound BoundOf(std::span<const GuidePosition> positions,
                   const Eigen::Vector3d& noise_std_mps2,
                   const std::array<double, 3>& target,
                   const GuideOptions& options) {
  std::vector<BoundPosition> bp;
  bp.reserve(positions.size());
  for (const GuidePosition& p : positions) {
    bp.push_back(AsBoundPosition(p.mean_mps2, p.samples, noise_std_mps2));
  }
  return BoundOfPositions(bp, target, options);
}

namespace internal {

double AngleDeg(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  return std::acos(std::clamp(u.normalized().dot(v.normalized()), -1.0, 1.0)) * 180.0 /
         std::numbers::pi;
}

int NearestCube(const Eigen::Vector3d& direction, double* off_deg) {
  const auto& cube = CanonicalDirections();
  int best = 0;
  double best_deg = 360.0;
  for (std::size_t k = 0; k < cube.size(); ++k) {
    const double deg = AngleDeg(direction, cube[k].direction);
    if (deg < best_deg) {
      best_deg = deg;
      best = static_cast<int>(k);
    }
  }
  *off_deg = best_deg;
  return best;
}

Eigen::Vector3d PooledNoise(std::span<const GuidePosition> positions) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double dof = 0.0;
  for (const GuidePosition& p : positions) {
    if (p.samples < 2) continue;
    const double n1 = static_cast<double>(p.samples - 1);
    sum += n1 * p.std_mps2.cwiseAbs2();
    dof += n1;
  }
  if (dof <= 0.0) return Eigen::Vector3d::Zero();
  return (sum / dof).cwiseSqrt();
}

std::size_t MedianSamples(std::span<const GuidePosition> positions) {
  std::vector<std::size_t> n;
  n.reserve(positions.size());
  for (const GuidePosition& p : positions) n.push_back(p.samples);
  if (n.empty()) return 0;
  const auto mid = n.begin() + static_cast<std::ptrdiff_t>((n.size() - 1) / 2);
  std::nth_element(n.begin(), mid, n.end());
  return *mid;
}

std::array<double, 3> Targets(const Eigen::Vector3d& noise_std_mps2,
                              std::size_t samples,
                              const GuideOptions& options) {
  std::array<double, 3> given = {
      options.target_bias_mps2, options.target_scale, options.target_angle_rad};
  std::array<double, 3> target = given;
  if (given[0] > 0.0 && given[1] > 0.0 && given[2] > 0.0) return target;
  // The full cube at the same holds and noise: its largest bound per group.
  std::vector<BoundPosition> cube;
  const Eigen::Vector3d noise = noise_std_mps2.cwiseMax(1e-12);
  for (const CanonicalDirection& d : CanonicalDirections()) {
    cube.push_back(
        AsBoundPosition(d.direction, std::max<std::size_t>(samples, 1), noise));
  }
  const std::array<double, 3> ones = {1.0, 1.0, 1.0};
  const GuideBound full = BoundOfPositions(cube, ones, options);
  std::array<double, 3> largest = {0.0, 0.0, 0.0};
  for (int i = 0; i < kNumModelParameters; ++i) {
    auto& g = largest[static_cast<std::size_t>(GroupOf(i))];
    const double s = full.std[static_cast<std::size_t>(i)];
    if (Finite(s)) g = std::max(g, s);
  }
  for (std::size_t g = 0; g < 3; ++g) {
    if (given[g] > 0.0) continue;
    // The angles of the 6-parameter model are not estimated: no target.
    target[g] = largest[g] > 0.0 ? options.target_factor * largest[g]
                                 : std::numeric_limits<double>::infinity();
  }
  return target;
}

int NextTargetOf(std::span<const GuidePosition> positions,
                 const std::vector<bool>& held,
                 const Eigen::Vector3d& noise_std_mps2,
                 const std::array<double, 3>& target,
                 const GuideOptions& options) {
  const auto& cube = CanonicalDirections();
  std::vector<BoundPosition> bp;
  for (const GuidePosition& p : positions) {
    bp.push_back(AsBoundPosition(p.mean_mps2, p.samples, noise_std_mps2));
  }
  const std::size_t samples = std::max<std::size_t>(MedianSamples(positions), 1);
  int best = -1;
  double best_ratio = std::numeric_limits<double>::infinity();
  int farthest = -1;
  double farthest_deg = -1.0;
  for (std::size_t k = 0; k < cube.size(); ++k) {
    if (held[k]) continue;
    double nearest_deg = 180.0;
    for (const GuidePosition& p : positions) {
      nearest_deg = std::min(nearest_deg, AngleDeg(p.mean_mps2, cube[k].direction));
    }
    if (nearest_deg > farthest_deg + 1e-9) {
      farthest_deg = nearest_deg;
      farthest = static_cast<int>(k);
    }
    bp.push_back(AsBoundPosition(cube[k].direction, samples, noise_std_mps2));
    const GuideBound b = BoundOfPositions(bp, target, options);
    bp.pop_back();
    if (b.determined && b.worst_ratio < best_ratio) {
      best_ratio = b.worst_ratio;
      best = static_cast<int>(k);
    }
  }
  return best >= 0 ? best : farthest;
}

}  // namespace internal
}  // namespace mpcal
