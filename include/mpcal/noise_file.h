/// \file noise_file.h
/// \brief The files of the noise analysis: its JSON (`mpcal.noise/1`, read
/// back by the report), Kalibr's IMU YAML, the truth of a simulated still
/// record, and the CSV of a still record written row by row.
///
/// JSON layout (SI; every key carries its unit):
///
///     {"format": "mpcal.noise/1", "input": "still.csv",
///      "segment": {"kind": "whole_record", "begin": 0, "end": 11520000,
///                  "static_intervals": 1},
///      "rate_hz": 400, "record_s": 28800, "samples": ..., "gaps": 0,
///      "confidence": 0.95,
///      "accelerometer": {"mean_mps2": [..],
///                        "record_needed_s": {"bias_instability": .. or null,
///                                            "random_walk": .., ...},
///                        "axes": {"x": {
///         "white_noise_mps2_per_rthz": {"status": "measured", "value": ..,
///                                       "lo": .., "hi": .., "tau_range_s": [..]},
///         "random_walk_mps3_per_rthz": {"status": "not_seen",
///                                       "upper_bound": .., "record_needed_s": ..},
///         "bias_instability_mps2", "quantisation_mps", "rate_ramp_mps3",
///         "adev_min_mps2", "adev_min_tau_s",
///         "allan": {"tau_s": [..], "adev_mps2": [..], "adev_lo_mps2": [..],
///                   "adev_hi_mps2": [..], "edf": [..], "noise_type": [..]}}, ..}},
///      "gyroscope": {... the same with rad/s units: white_noise_radps_per_rthz,
///                    bias_instability_radps, random_walk_radps2_per_rthz,
///                    quantisation_rad, rate_ramp_radps2, adev_radps ...}}
#pragma once

#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mpcal/noise.h"
#include "mpcal/simulate_noise.h"

namespace mpcal {

/// The JSON key of a term for a sensor, e.g. "random_walk_radps2_per_rthz".
std::string NoiseTermKey(NoiseTerm term, bool gyroscope);

/// The JSON text of a noise analysis of `input`.
std::string NoiseJson(const NoiseResult& result,
                      const std::string& input,
                      double confidence);

/// A noise JSON read back.
struct NoiseFile {
  NoiseResult result;
  std::string input;
  double confidence = 0.95;
};
/// \throws mpcal::Error naming the file and field for a missing, malformed
///   or other-version file.
NoiseFile ReadNoiseFile(const std::string& path);
/// The same from text; `origin` names it in messages.
NoiseFile ParseNoiseJson(const std::string& text, const std::string& origin);

/// What went into the Kalibr file: for each of its four values, the axis it
/// came from and whether it is an upper bound (not measured on that axis).
struct KalibrValue {
  double value = 0.0;
  int axis = 0;                           ///< 0, 1, 2: x, y, z
  bool upper_bound = false;               ///< not measured: the bound from the record
  std::optional<double> record_needed_s;  ///< when a bound: to measure it
};
struct KalibrFile {
  std::string text;
  /// As the record gave them (measured or bounds), before any inflation.
  KalibrValue accel_noise_density, accel_random_walk, gyro_noise_density,
      gyro_random_walk;
  /// The factor the user asked every noise density and random walk to be
  /// multiplied by in the file (1: as measured); Written() gives a value as
  /// the file holds it.
  double inflate = 1.0;
  double Written(const KalibrValue& v) const { return v.value * inflate; }
};

/// Empty when `inflate` is a factor a filter file may carry (finite, at
/// least 1: an inflation never makes a filter trust the sensor more than the
/// record does); otherwise what is wrong with it.
std::string ValidateInflation(double inflate);

/// Kalibr's IMU YAML (accelerometer_noise_density, accelerometer_random_walk,
/// gyroscope_noise_density, gyroscope_random_walk, update_rate, rostopic).
/// Rule across axes: the largest of the three measured values (Kalibr takes
/// one value per sensor; the largest keeps the filter from trusting any axis
/// more than it deserves). A bound never wins over a measured value: only
/// when no axis measured the term is the value the largest upper bound,
/// marked UPPER BOUND on its own line; the axes not measured are named in
/// the comment either way. Densities are Kalibr's
/// continuous-time ones, the same as mpcal's. `inflate` (≥ 1, asked for by
/// the user): the four values written are the measured ones times it, and
/// the file says so in its header and beside each value with the measured
/// one.
/// \throws mpcal::Error when the result has no gyroscope, a white noise or
///   random walk has neither a value nor a bound, or `inflate` is not valid
///   (ValidateInflation).
KalibrFile KalibrYaml(const NoiseResult& result,
                      const std::string& input,
                      const std::string& rostopic,
                      double inflate = 1.0);

/// The truth of a simulated still record (`mpcal.noise_truth/1`), in the
/// same keys as the noise JSON.
std::string NoiseTruthJson(const NoiseSimulationOptions& options);

/// Writes a still record as CSV: header t,ax,ay,az,gx,gy,gz (s, m/s²,
/// rad/s), then `next` until it returns false; `significant_digits` per
/// value (time exact). Calls `progress` with the fraction of `rows` done.
/// \throws mpcal::Error when `out` fails.
void WriteImuCsv(
    std::ostream& out,
    const std::function<bool(double*, Eigen::Vector3d*, Eigen::Vector3d*)>& next,
    int significant_digits,
    std::size_t rows,
    const std::function<void(double)>& progress);

}  // namespace mpcal
