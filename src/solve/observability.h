// Which parameters a set of positions determines. Gravity's magnitude sees
// the sensor only through the directions it was held in: positions that do
// not span the sphere leave combinations of parameters undetermined
// (docs/method.md §3.9), and the user must be told which ones.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace mpcal::internal {

struct Observability {
  /// Parameters in a direction of parameter space that the data constrain no
  /// better than 1 % of the plausible range of the parameters (bias 1 g,
  /// scale-factor error 0.5, angle 0.5 rad).
  std::vector<std::string> undetermined;
  /// Parameters whose 1σ is inflated by correlation with the others far
  /// beyond what a well-spread session gives (variance inflation factor).
  std::vector<std::string> poorly_determined;
  /// Smallest singular value of the range-scaled Jacobian: the 1σ, in units
  /// of the plausible range, of the worst-determined parameter combination.
  double weakest_direction_sigma = 0.0;
};

/// `jacobian`: whitened residuals × estimated parameters (packed order);
/// `names`: one per column.
Observability AnalyseObservability(const Eigen::MatrixXd& jacobian,
                                   const std::vector<std::string>& names);

}  // namespace mpcal::internal
