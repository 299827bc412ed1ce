// Monte Carlo studies of the whole pipeline (simulate → detect → solve), as
// a user runs it: sessions drawn at random within a stated envelope of
// devices, and each estimate compared with the truth and with the
// Cramér-Rao bound of its own session.
#pragma once

#include <cmath>
#include <optional>
#include <random>

#include <Eigen/Core>

#include "mpcal/calibrate.h"
#include "mpcal/error.h"
#include "mpcal/simulate.h"
#include "simulated_bound.h"

namespace mpcal::bench {

/// The envelope sessions are drawn from.
struct Envelope {
  double max_bias_g = 0.3;
  double max_scale_error = 0.06;
  double max_angle_rad = 0.02;
  int min_positions = 14;
  int max_positions = 30;
  double min_rate_hz = 50.0;
  double max_rate_hz = 200.0;
  double noise_density_mps2_per_sqrt_hz = 0.002;
  /// A bias drift drawn per axis within ± this (m/s² per s); 0: none (and
  /// no random draw, so that sessions without drift stay as they were).
  double max_bias_drift_mps2_per_s = 0.0;
};

/// A session drawn from the envelope, in g or m/s² at random.
inline SimulateStaticOptions DrawSession(const Envelope& e, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  SimulateStaticOptions o;
  o.device = FindPreset("mti-g");
  o.device.name = "random";
  ErrorModel& m = o.device.truth;
  for (int i = 0; i < 3; ++i) {
    m.bias_mps2[i] = e.max_bias_g * kStandardGravityMps2 * u(rng);
    m.scale_factor_error[i] = e.max_scale_error * u(rng);
  }
  m.theta_yz_rad = e.max_angle_rad * u(rng);
  m.theta_zx_rad = e.max_angle_rad * u(rng);
  m.theta_zy_rad = e.max_angle_rad * u(rng);
  o.device.noise_density_mps2_per_sqrt_hz = e.noise_density_mps2_per_sqrt_hz;
  o.device.range_mps2 = 0.0;
  o.device.resolution_mps2 = 0.0;
  std::uniform_int_distribution<int> positions(e.min_positions, e.max_positions);
  o.positions = positions(rng);
  o.rate_hz = e.min_rate_hz + (e.max_rate_hz - e.min_rate_hz) * 0.5 * (1.0 + u(rng));
  o.units = u(rng) > 0.0 ? AccelUnits::kG : AccelUnits::kMps2;
  o.seed = rng();
  if (e.max_bias_drift_mps2_per_s > 0.0) {
    // Half to all of the largest drift on each axis, either sign: a drift the
    // session can see (a smaller one is indistinguishable from none).
    for (int i = 0; i < 3; ++i) {
      const double v = u(rng);
      o.bias_drift_mps2_per_s[i] = e.max_bias_drift_mps2_per_s * (v < 0.0 ? -1.0 : 1.0) *
                                   (0.5 + 0.5 * std::abs(v));
    }
  }
  return o;
}

/// One session through the pipeline: the error and the reported 1σ, both in
/// units of the bound; nullopt when calibration failed (thrown or did not
/// converge).
struct Outcome {
  Eigen::Matrix<double, 9, 1> error_over_bound;
  Eigen::Matrix<double, 9, 1> reported_over_bound;
  /// (estimate − truth)/reported 1σ: standard normal when the 1σ is honest.
  Eigen::Matrix<double, 9, 1> z;
  /// Whether the calibration chose a drifting bias.
  bool drift_chosen = false;
  /// Whether the split-half check widened the 1σ (its halves disagreed).
  bool widened = false;
};

inline std::optional<Outcome> RunSession(const SimulateStaticOptions& options) {
  const SimulatedSession s = SimulateStatic(options);
  CalibrateOptions calibrate;
  calibrate.solve.cross_validate = false;  // does not change the estimate
  try {
    const CalibrateResult r = CalibrateRecording(s.recording, calibrate);
    if (!r.solve.converged()) return std::nullopt;
    // The bound of the model the calibration chose: with the drift
    // estimated, or with a constant bias. Either way the estimate's bias is
    // the bias at the solver's reference time (the middle of the used
    // positions); the truth's is at its own reference (the last sample), so
    // it is moved there first. Comparing a constant-bias estimate with the
    // bias at the last sample charged the estimator with d·(t_end − t_ref),
    // several bounds for the sessions whose drift the F test did not pick up.
    SimulatedSession as_chosen = s;
    if (s.truth.bias_drift) {
      const BiasDrift& truth_drift = *s.truth.bias_drift;
      as_chosen.truth.model.bias_mps2 +=
          truth_drift.mps2_per_s *
          (r.solve.bias_reference_time_s - truth_drift.reference_time_s);
    }
    if (r.calibration.bias_drift) {
      BiasDrift moved = s.truth.bias_drift.value_or(BiasDrift{});
      moved.reference_time_s = r.calibration.bias_drift->reference_time_s;
      as_chosen.truth.bias_drift = moved;
    } else {
      as_chosen.truth.bias_drift.reset();
    }
    const Eigen::Matrix<double, 9, 1> bound =
        SimulatedBoundSigma(as_chosen, options.initial_rest_s);
    const Eigen::Matrix<double, 9, 1> error =
        ToVector(r.calibration.model) - ToVector(as_chosen.truth.model);
    const Eigen::Matrix<double, 9, 1> reported = ToVector(*r.calibration.std);
    return Outcome{error.cwiseQuotient(bound),
                   reported.cwiseQuotient(bound),
                   error.cwiseQuotient(reported),
                   r.calibration.bias_drift.has_value(),
                   r.solve.split_half && r.solve.split_half->widening > 1.0};
  } catch (const Error&) {
    return std::nullopt;
  }
}

}  // namespace mpcal::bench
