// Which entries of M a session's turns determine: each turn sees the
// gyroscope only through the axes it turns about, so a session that never
// turns about an axis leaves that column of M undetermined (docs/method.md §7).
#pragma once

#include <vector>

#include <Eigen/Core>

#include "mpcal/gyro.h"

namespace mpcal::internal {

/// Findings from the whitened Jacobian of the turn residuals with respect to
/// the 9 entries of M (row-major), `dof_scale` the factor on the covariance
/// (variance factor), `poorly_determined_std` as in GyroOptions. Fills
/// `singular_values` (of the Jacobian, largest first).
std::vector<GyroFinding> AnalyseGyroObservability(
    const Eigen::MatrixXd& jacobian,
    double covariance_scale,
    double poorly_determined_std,
    Eigen::Matrix<double, 9, 1>* singular_values);

}  // namespace mpcal::internal
