#include "split_half.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include <Eigen/Cholesky>

#include "mpcal/distributions.h"
#include "mpcal/error.h"

namespace mpcal::internal {
namespace {

using Vector9 = Eigen::Matrix<double, kNumModelParameters, 1>;

// Redundant positions each half needs for the check
// (SplitRedundancyNeeded). By time, a half has its own orientations and
// estimates its own scatter (which needs 5 redundant positions; weights.h):
// fewer would leave its 1σ resting on a barely determined fit. Interleaved,
// the halves share the orientations of the whole and take its scatter
// (SolveOptions::known_position_scatter_mps2), so they are two samples of one
// design: 3, as for the drift's test, is enough for the linearised 1σ
// (tests/solve/split_half_test.cc measures the false alarms of 13 + 13).

}  // namespace

std::array<std::vector<std::size_t>, 2> InterleavedHalves(
    std::span<const PositionObservation> positions) {
  // Pairs of nearest orientations, in recording order: each position not yet
  // paired takes the unpaired one whose mean points nearest its own, and
  // the halves get one of each pair, the earlier alternately in the first
  // and the second. A position left alone goes to the smaller half.
  const std::size_t count = positions.size();
  std::vector<bool> paired(count, false);
  std::array<std::vector<std::size_t>, 2> halves;
  std::size_t pairs = 0;
  for (std::size_t k = 0; k < count; ++k) {
    if (paired[k]) continue;
    paired[k] = true;
    const Eigen::Vector3d u = positions[k].mean_mps2.normalized();
    std::optional<std::size_t> nearest;
    double best = -2.0;
    for (std::size_t j = k + 1; j < count; ++j) {
      if (paired[j]) continue;
      const double cosine = u.dot(positions[j].mean_mps2.normalized());
      if (cosine > best) {
        best = cosine;
        nearest = j;
      }
    }
    if (!nearest) {
      halves[halves[0].size() <= halves[1].size() ? 0 : 1].push_back(k);
      continue;
    }
    paired[*nearest] = true;
    const std::size_t first = pairs % 2;
    halves[first].push_back(k);
    halves[1 - first].push_back(*nearest);
    ++pairs;
  }
  for (auto& half : halves) std::sort(half.begin(), half.end());
  return halves;
}

namespace {

// The two halves of the used positions: the first ⌈K/2⌉ in recording order
// and the rest, or the interleaved halves of paired orientations.
std::array<std::vector<PositionObservation>, 2> Halves(
    std::span<const PositionObservation> positions,
    const std::vector<bool>& used,
    SplitKind kind) {
  std::vector<PositionObservation> in_use;
  for (std::size_t k = 0; k < positions.size(); ++k) {
    if (used[k]) in_use.push_back(positions[k]);
  }
  std::array<std::vector<PositionObservation>, 2> halves;
  if (kind == SplitKind::kInterleaved) {
    const auto index = InterleavedHalves(in_use);
    for (int h = 0; h < 2; ++h) {
      for (std::size_t k : index[h]) halves[h].push_back(in_use[k]);
    }
    return halves;
  }
  const std::size_t first = (in_use.size() + 1) / 2;
  for (std::size_t k = 0; k < in_use.size(); ++k) {
    halves[k >= first ? 1 : 0].push_back(in_use[k]);
  }
  return halves;
}

// The fit of one half, or nullopt when it does not determine the model.
std::optional<SolveResult> FitHalf(const std::vector<PositionObservation>& half,
                                   const SolveOptions& options) {
  try {
    SolveResult r = Solve(half, options);
    if (!r.converged()) return std::nullopt;
    return r;
  } catch (const Error&) {
    return std::nullopt;
  }
}

SplitHalfComparison Compare(std::span<const PositionObservation> positions,
                            const std::vector<bool>& used,
                            SplitKind kind,
                            const SolveOptions& half_options) {
  const auto halves = Halves(positions, used, kind);
  SplitHalfComparison c;
  c.kind = kind;
  c.positions_first = static_cast<int>(halves[0].size());
  c.positions_second = static_cast<int>(halves[1].size());
  // A half with few redundant positions is nearly as many equations as
  // unknowns: its 1σ rests on the linearisation of a barely determined fit
  // and would make the halves look inconsistent when they are not.
  const int needed = ParameterCount(half_options.model) +
                     (half_options.force_bias_drift ? 3 : 0) +
                     SplitRedundancyNeeded(kind);
  if (std::min(c.positions_first, c.positions_second) < needed) return c;
  const auto first = FitHalf(halves[0], half_options);
  if (!first) return c;
  const auto second = FitHalf(halves[1], half_options);
  if (!second) return c;
  const int p = ParameterCount(half_options.model);
  const Vector9 d = ToVector(first->estimate) - ToVector(second->estimate);
  const Eigen::MatrixXd covariance =
      (first->covariance + second->covariance).topLeftCorner(p, p);
  double sum_sq = 0.0;
  for (int i = 0; i < p; ++i) {
    const double z = d[i] / std::sqrt(covariance(i, i));
    c.z.push_back(z);
    sum_sq += z * z;
  }
  c.determined =
      std::all_of(c.z.begin(), c.z.end(), [](double z) { return std::isfinite(z); });
  if (!c.determined) {
    c.z.clear();
    return c;
  }
  c.rms_z = std::sqrt(sum_sq / p);
  // With the correlations: the parameters of one half are not independent.
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(covariance);
  const Eigen::VectorXd dp = d.head(p);
  const double mahalanobis = dp.dot(ldlt.solve(dp));
  c.chi2 =
      ldlt.info() == Eigen::Success && ldlt.isPositive() && std::isfinite(mahalanobis)
          ? mahalanobis
          : sum_sq;
  c.dof = p;
  c.p_value = ChiSquareUpperTail(c.chi2, p);
  return c;
}

}  // namespace

double JudgeSplits(std::vector<SplitHalfComparison>& comparisons, double significance) {
  // The significance is the whole check's: of a session whose 1σ is honest,
  // one in 1/significance is widened, however many splits were made
  // (Bonferroni: each split at significance/n). Two splits tested at the full
  // significance each would widen twice as many honest sessions, each by at
  // least √(χ²₀.₉₉(9)/9) = 1.55.
  const double per_split = PerSplitSignificance(comparisons, significance);
  double widening = 1.0;
  for (SplitHalfComparison& c : comparisons) {
    if (!c.determined) continue;
    c.disagree = c.p_value < per_split;
    if (c.disagree) widening = std::max(widening, std::sqrt(c.chi2 / c.dof));
  }
  return widening;
}

SplitHalfSummary CheckSplitHalves(std::span<const PositionObservation> positions,
                                  const std::vector<bool>& used,
                                  const SolveOptions& options) {
  SolveOptions half_options = options;
  half_options.cross_validate = false;
  half_options.split_half_check = false;
  SplitHalfSummary summary;
  summary.significance = options.split_half_significance;
  for (SplitKind kind : {SplitKind::kByTime, SplitKind::kInterleaved}) {
    summary.comparisons.push_back(Compare(positions, used, kind, half_options));
  }
  summary.widening = JudgeSplits(summary.comparisons, summary.significance);
  return summary;
}

}  // namespace mpcal::internal
