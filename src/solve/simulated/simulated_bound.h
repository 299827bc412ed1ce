/// \file simulated_bound.h
/// \brief The Cramér-Rao bound of a simulated session: the yardstick the
/// demo, the tests and the accuracy benchmark hold every estimate against.
///
/// Not a public header: it ties the simulator to the solver, which a user of
/// the library never needs. Link the non-installed interface library
/// `mpcal_simulated_bound` (src/solve/CMakeLists.txt) to include it.
#pragma once

#include <cmath>
#include <vector>

#include <Eigen/Core>

#include "mpcal/cramer_rao.h"
#include "mpcal/simulate.h"

namespace mpcal {

/// 1σ of the bound (packed order of kParameterNames) with all the still
/// samples of each position. The initial rest of `initial_rest_s` seconds is
/// a static position too, and the estimator uses it: so does the bound, its
/// direction being the truth applied to its mean. Quantisation enters as
/// step²/12 of extra variance. The detector trims settling at each end, so an
/// estimate can at best come within a few % of this.
/// \throws mpcal::Error as CramerRaoBound.
/// With a drifting bias in the truth (truth.bias_drift), the bound when the
/// drift is estimated too.
inline Eigen::Matrix<double, 9, 1> SimulatedBoundSigma(
    const SimulatedSession& session,
    double initial_rest_s,
    ModelKind model = ModelKind::kShinElSheimy9) {
  const auto& drift = session.truth.bias_drift;
  const double reference_s = drift ? drift->reference_time_s : 0.0;
  const double quantisation_var = std::pow(session.quantisation_step_mps2, 2) / 12.0;
  const Eigen::Vector3d noise =
      (session.noise_std_mps2.cwiseAbs2().array() + quantisation_var).sqrt().matrix();
  std::vector<BoundPosition> positions;
  const auto rest_samples = static_cast<std::size_t>(initial_rest_s * session.rate_hz);
  if (rest_samples > 0) {
    Eigen::Vector3d mean = Eigen::Vector3d::Zero();
    for (std::size_t i = 0; i < rest_samples; ++i) mean += session.recording.accel[i];
    mean /= static_cast<double>(rest_samples);
    positions.push_back({session.truth.Correct(mean).normalized(),
                         noise,
                         rest_samples,
                         0.5 * initial_rest_s - reference_s});
  }
  for (std::size_t k = 0; k < session.directions.size(); ++k) {
    const auto [first, last] = session.still_ranges[k];
    positions.push_back(
        {session.directions[k],
         noise,
         last - first,
         0.5 * static_cast<double>(first + last) / session.rate_hz - reference_s});
  }
  return (drift ? CramerRaoBoundWithDrift(
                      session.truth.model, positions, session.truth.gravity_mps2, model)
                : CramerRaoBound(
                      session.truth.model, positions, session.truth.gravity_mps2, model))
      .diagonal()
      .cwiseSqrt();
}

}  // namespace mpcal
