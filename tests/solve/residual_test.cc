// The automatic derivatives of the residual against numeric ones
// (ceres::GradientChecker), at a consumer-grade point.
#include "solve/residual.h"

#include <ceres/ceres.h>
#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include "synthetic_positions.h"

namespace mpcal::internal {
namespace {

TEST(MagnitudeResidual, AutomaticDerivativesMatchNumericOnes) {
  const ErrorModel m = testing::ConsumerGrade();
  double p[kNumModelParameters];
  m.ToParameters(p);
  // Tilted directions: on exact cube directions some derivatives are zero and
  // the checker's relative error compares rounding noise with rounding noise.
  std::mt19937_64 rng(11);
  for (const Eigen::Vector3d& u : testing::Tilted(testing::CubeDirections(), 0.2, rng)) {
    // 1 % off gravity: at a zero residual the checker's relative comparison
    // of residuals would compare rounding noise with rounding noise.
    const Eigen::Vector3d reading = m.Forward(1.01 * testing::kTestGravityMps2 * u);
    ceres::AutoDiffCostFunction<MagnitudeResidual, 1, 3, 3, 3> cost(
        new MagnitudeResidual(reading, testing::kTestGravityMps2, 0.01));
    ceres::NumericDiffOptions numeric;
    const std::vector<const ceres::Manifold*>* no_manifolds = nullptr;
    ceres::GradientChecker checker(&cost, no_manifolds, numeric);
    ceres::GradientChecker::ProbeResults results;
    const double* blocks[] = {p, p + 3, p + 6};
    EXPECT_TRUE(checker.Probe(blocks, 1e-7, &results)) << results.error_log;
  }
}

}  // namespace
}  // namespace mpcal::internal
