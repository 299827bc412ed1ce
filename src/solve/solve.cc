// The multi-position least squares (Souza & Machado 2016, eq 12) with Ceres,
// with outlier positions excluded and every position cross-validated: Solve
// takes the named steps of solve_steps.h in turn.
#include "mpcal/solve.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include <fmt/format.h>

#include "fit.h"
#include "mpcal/error.h"
#include "mpcal/plausible.h"
#include "solve_steps.h"
#include "weights.h"

namespace mpcal {

std::string_view ToString(RobustLoss loss) {
  switch (loss) {
    case RobustLoss::kNone:
      return "none";
    case RobustLoss::kHuber:
      return "huber";
    case RobustLoss::kCauchy:
      return "cauchy";
  }
  return "unknown";
}

std::optional<RobustLoss> ParseRobustLoss(std::string_view name) {
  for (RobustLoss l : {RobustLoss::kNone, RobustLoss::kHuber, RobustLoss::kCauchy}) {
    if (name == ToString(l)) return l;
  }
  return std::nullopt;
}

std::string_view ToString(SolveStatus status) {
  return status == SolveStatus::kConverged ? "converged" : "no convergence";
}

std::string SolveOptions::Validate() const {
  if (!IsPlausibleGravity(gravity_mps2)) {
    return fmt::format("gravity_mps2 = {} is not a gravity on Earth ({}..{} m/s2)",
                       gravity_mps2,
                       kMinGravityMps2,
                       kMaxGravityMps2);
  }
  if (max_iterations < 1) return "max_iterations must be at least 1";
  if (!(outlier_threshold > 1.0)) return "outlier_threshold must be above 1";
  if (!(split_half_significance > 0.0 && split_half_significance < 1.0)) {
    return "split_half_significance must be in (0, 1)";
  }
  if (known_position_scatter_mps2 && !(*known_position_scatter_mps2 >= 0.0 &&
                                       std::isfinite(*known_position_scatter_mps2))) {
    return "known_position_scatter_mps2 must be finite and >= 0";
  }
  return "";
}

std::string SolveResult::BriefReport() const {
  return fmt::format(
      "{} after {} iterations; |a|-g RMS {:.3g} -> {:.3g} m/s2; variance factor {:.3g}",
      ToString(status),
      iterations,
      residual_rms_before_mps2,
      residual_rms_after_mps2,
      variance_factor);
}

SolveResult Solve(std::span<const PositionObservation> positions,
                  const SolveOptions& options) {
  using namespace internal;
  CheckSolveInput(positions, options);
  const std::size_t count = positions.size();
  SolveResult result;
  result.used = std::vector<bool>(
      count,
      true);  // not assign(): GCC 12 warns of a null dereference inside vector<bool>
  result.initial = InitialiseSixPosition(positions, options.gravity_mps2);
  ErrorModel nominal;
  nominal.bias_mps2 = options.nominal_offset_mps2;
  result.residual_before_mps2 =
      MagnitudeResiduals(nominal, positions, options.gravity_mps2);
  const std::vector<Eigen::Vector3d> noise = UsableNoise(positions);

  auto fit = std::make_unique<Fit>(
      Select(positions, noise, result.used), result.initial, options);
  fit->Run();
  result.iterations = fit->iterations();
  if (options.exclude_outliers) ExcludeOutliers(positions, noise, options, fit, result);

  const double reference_s = BiasReferenceTime(positions, result.used, options);
  result.bias_reference_time_s = reference_s;
  if (options.consider_bias_drift || options.force_bias_drift) {
    ChooseBiasDrift(
        Select(positions, noise, result.used), options, reference_s, fit, result);
  }
  if (!JudgeFit(positions, options, reference_s, *fit, result)) return result;

  const int p = ParameterCount(options.model);
  const int dof =
      static_cast<int>(std::count(result.used.begin(), result.used.end(), true)) -
      (p + (fit->drifts() ? 3 : 0));
  WarnAboutDetermination(count, p, dof, *fit, result);
  CrossValidate(positions, noise, options, dof, *fit, result);
  SetCovariance(dof, *fit, result);
  if (options.split_half_check) {
    // The halves fit the model the whole chose: with a drifting bias,
    // reported at the same time as the whole's, or a constant one (a half
    // choosing a drift by chance would compare two different models).
    SolveOptions split_options = options;
    split_options.bias_reference_time_s = reference_s;
    split_options.force_bias_drift = result.bias_drift.has_value();
    split_options.consider_bias_drift = result.bias_drift.has_value();
    // Halves too small to estimate the scatter take the whole session's.
    split_options.known_position_scatter_mps2 = result.position_scatter_mps2;
    WidenBySplitHalves(positions, split_options, result);
  }
  return result;
}

}  // namespace mpcal
