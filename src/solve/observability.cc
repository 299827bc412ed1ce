#include "observability.h"

#include <cmath>

#include <Eigen/SVD>

#include "mpcal/model.h"
#include "mpcal/units.h"

namespace mpcal::internal {
namespace {

// The plausible range of each kind of parameter for any MEMS part: a
// parameter known no better than this is not known at all.
constexpr double kBiasRangeMps2 = kStandardGravityMps2;  // 1 g
constexpr double kScaleRange = 0.5;
constexpr double kAngleRangeRad = 0.5;

// A combination of parameters known no better than this share of the
// plausible range is undetermined. An axis that never sees gravity is still
// "excited" at the noise level of its readings, which gives it a singular
// value of order √K whatever the noise (1σ ≈ range/√K): spurious, and far
// below the ≥ g/σ·√K of any real information, so 1 % separates the two.
constexpr double kUndeterminedShareOfRange = 0.01;
// A parameter is named in a weak direction when it carries at least this
// share of the singular vector.
constexpr double kWeakVectorShare = 0.3;
// Variance inflation beyond which a parameter is called poorly determined.
// The 26 cube positions give at most ~4; positions crowded in one
// hemisphere reach hundreds.
constexpr double kPoorInflationFactor = 50.0;

double Range(Eigen::Index packed_index) {
  if (packed_index < 3) return kBiasRangeMps2;
  if (packed_index < 6) return kScaleRange;
  return kAngleRangeRad;
}

}  // namespace

Observability AnalyseObservability(const Eigen::MatrixXd& jacobian,
                                   const std::vector<std::string>& names) {
  Observability result;
  const Eigen::Index n = jacobian.cols();
  // Columns in units of each parameter's plausible range: a singular value s
  // is a combination whose 1σ is range/s.
  Eigen::VectorXd range(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    // A drifting bias (its rates come after the model's parameters):
    // plausibly up to 1 g over a session of 1000 s.
    const bool drift = names[static_cast<std::size_t>(j)].starts_with("bias_drift");
    range[j] = drift ? kBiasRangeMps2 / 1000.0 : Range(j);
  }
  const Eigen::MatrixXd scaled = jacobian * range.asDiagonal();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(scaled, Eigen::ComputeFullV);
  const Eigen::VectorXd& sv = svd.singularValues();
  result.weakest_direction_sigma = sv.size() == n && sv[n - 1] > 0.0
                                       ? 1.0 / sv[n - 1]
                                       : std::numeric_limits<double>::infinity();

  std::vector<bool> named(static_cast<std::size_t>(n), false);
  for (Eigen::Index k = 0; k < n; ++k) {
    const double singular = k < sv.size() ? sv[k] : 0.0;
    if (singular * kUndeterminedShareOfRange >= 1.0) continue;
    const Eigen::VectorXd v = svd.matrixV().col(k);
    for (Eigen::Index j = 0; j < n; ++j) {
      if (std::abs(v[j]) >= kWeakVectorShare && !named[static_cast<std::size_t>(j)]) {
        named[static_cast<std::size_t>(j)] = true;
        result.undetermined.push_back(names[static_cast<std::size_t>(j)]);
      }
    }
  }
  if (!result.undetermined.empty()) return result;

  // Variance inflation: with unit-norm columns, (NᵀN)⁻¹_jj is 1 for a
  // parameter uncorrelated with all the others.
  const Eigen::VectorXd norms = scaled.colwise().norm().transpose();
  const Eigen::MatrixXd normalised = scaled * norms.cwiseInverse().asDiagonal();
  const Eigen::MatrixXd inverse =
      (normalised.transpose() * normalised).ldlt().solve(Eigen::MatrixXd::Identity(n, n));
  for (Eigen::Index j = 0; j < n; ++j) {
    if (inverse(j, j) > kPoorInflationFactor) {
      result.poorly_determined.push_back(names[static_cast<std::size_t>(j)]);
    }
  }
  return result;
}

}  // namespace mpcal::internal
