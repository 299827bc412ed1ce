#include "gyro_observability.h"

#include <algorithm>
#include <cmath>

#include <Eigen/SVD>

namespace mpcal::internal {
namespace {

// A combination of entries of M known no better than this (1σ) is
// undetermined: a tenth of the plausible range of any entry (0.5). An axis
// never turned about is still "excited" by the gyroscope's noise, which gives
// it a singular value of order √turns (1σ ≈ 0.2 for 30 turns), far below the
// hundreds of a turn of tens of degrees; this separates the two.
constexpr double kUndeterminedStd = 0.05;
// An entry is named in a weak direction when it carries this share of it.
constexpr double kWeakVectorShare = 0.3;

}  // namespace

std::vector<GyroFinding> AnalyseGyroObservability(
    const Eigen::MatrixXd& jacobian,
    double covariance_scale,
    double poorly_determined_std,
    Eigen::Matrix<double, 9, 1>* singular_values) {
  std::vector<GyroFinding> findings;
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(jacobian, Eigen::ComputeFullV);
  const Eigen::VectorXd& sv = svd.singularValues();
  singular_values->setZero();
  for (Eigen::Index k = 0; k < std::min<Eigen::Index>(sv.size(), 9); ++k) {
    (*singular_values)[k] = sv[k];
  }

  GyroFinding undetermined;
  undetermined.kind = GyroFindingKind::kUndetermined;
  undetermined.limit = kUndeterminedStd;
  for (int k = 0; k < 9; ++k) {
    const double s = (*singular_values)[k];
    const double std = s > 0.0 ? std::sqrt(covariance_scale) / s : INFINITY;
    if (std <= kUndeterminedStd) continue;
    undetermined.value = std::max(undetermined.value, std);
    const Eigen::VectorXd v = svd.matrixV().col(k);
    for (int j = 0; j < 9; ++j) {
      if (std::abs(v[j]) < kWeakVectorShare) continue;
      if (std::find(undetermined.parameters.begin(), undetermined.parameters.end(), j) ==
          undetermined.parameters.end()) {
        undetermined.parameters.push_back(j);
      }
      undetermined.turn_axes[static_cast<std::size_t>(j % 3)] = true;
    }
  }
  if (!undetermined.parameters.empty()) {
    std::sort(undetermined.parameters.begin(), undetermined.parameters.end());
    findings.push_back(undetermined);
    return findings;
  }

  const Eigen::MatrixXd information = jacobian.transpose() * jacobian;
  const Eigen::MatrixXd covariance =
      covariance_scale * information.ldlt().solve(Eigen::MatrixXd::Identity(9, 9));
  GyroFinding poor;
  poor.kind = GyroFindingKind::kPoorlyDetermined;
  poor.limit = poorly_determined_std;
  for (int j = 0; j < 9; ++j) {
    const double std = std::sqrt(std::max(covariance(j, j), 0.0));
    if (std <= poorly_determined_std) continue;
    poor.parameters.push_back(j);
    poor.turn_axes[static_cast<std::size_t>(j % 3)] = true;
    poor.value = std::max(poor.value, std);
  }
  if (!poor.parameters.empty()) findings.push_back(poor);
  return findings;
}

}  // namespace mpcal::internal
