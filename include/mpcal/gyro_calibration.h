/// \file gyro_calibration.h
/// \brief The gyroscope's calibration as a calibration file holds it: the
/// model ω = M (ω_raw − b), its 1σ, the bias measured at every static
/// position and how well the turns fit. Plain data; the estimator is in
/// gyro.h, the file in calibration_file.h.
///
/// Model (Tedaldi, Pretto & Menegatti, ICRA 2014; docs/method.md §7): a reading
/// `r` in the log's units is turned into nominal rad/s by `radps_per_unit`
/// (1 for rad/s, π/180 for deg/s, found from the data for raw counts), then
///
///     ω = M · (r · radps_per_unit − b)
///
/// with ω the angular rate of the body (rad/s) in the accelerometer's
/// orthogonal frame (model.h: x along the accelerometer's x axis, y in the
/// plane of its x and y axes), M a general 3×3 matrix (its diagonal the
/// scale factors 1 + s, its off-diagonal terms the misalignments and the
/// rotation between the two triads, rad) and b the bias (rad/s), which holds
/// the Earth rate projected on the body as well.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "mpcal/units.h"

namespace mpcal {

/// The bias measured at one static position (mean gyroscope reading there).
struct GyroBiasSample {
  double t_s = 0.0;  ///< centre of the position, in the log's clock
  Eigen::Vector3d bias_radps = Eigen::Vector3d::Zero();
};

/// How the gyroscope fit went (`"gyroscope.fit"` in the file).
struct GyroFitSummary {
  int turns = 0;
  /// RMS over the turns of the tilt between the gravity direction carried
  /// over each turn by the gyroscope and the one measured after it (rad):
  /// with the nominal scale and per-position bias (before) and calibrated.
  double residual_rms_before_rad = 0.0;
  double residual_rms_after_rad = 0.0;
  int iterations = 0;
  bool converged = false;
  /// χ² of the whitened turn residuals over their degrees of freedom.
  double variance_factor = 0.0;
  /// White noise of the gyroscope at rest (rad/s per sample, 1σ) and the
  /// sample period (s): its angle random walk is σ·√(period).
  double noise_std_radps = 0.0;
  double sample_period_s = 0.0;
};

struct GyroCalibration {
  /// Units of the gyroscope columns of the logs this applies to, and the
  /// nominal factor to rad/s applied before the model.
  GyroUnits input_units = GyroUnits::kRadps;
  double radps_per_unit = 1.0;
  /// M, applied to nominal rad/s.
  Eigen::Matrix3d m = Eigen::Matrix3d::Identity();
  /// The bias applied by Correct (rad/s, nominal units): the mean of the
  /// per-position biases (a fresh power-up needs a fresh rest to measure it).
  Eigen::Vector3d bias_radps = Eigen::Vector3d::Zero();
  /// 1σ of the bias: the spread of the per-position biases about their mean
  /// over √(positions), or the truth's zero.
  std::optional<Eigen::Vector3d> bias_std_radps;
  /// Covariance of the 9 entries of M, row-major (m_xx, m_xy, m_xz, m_yx, …);
  /// nullopt for a truth file.
  std::optional<Eigen::Matrix<double, 9, 9>> m_covariance;
  /// The bias at every static position (as measured, G f included), in
  /// time order; empty for a truth.
  std::vector<GyroBiasSample> position_bias;
  /// g-sensitivity G of the bias (rad/s per m/s², nominal units) when
  /// modelled: ω = M (r · radps_per_unit − b − G f), f the specific force
  /// (m/s²), and `bias_radps` is then the part of the bias without G f.
  std::optional<Eigen::Matrix3d> g_sensitivity_radps_per_mps2;
  std::optional<GyroFitSummary> fit;

  /// Angular rate (rad/s) from a reading in `input_units` (without the
  /// g-sensitivity term; see the overload).
  Eigen::Vector3d Correct(const Eigen::Vector3d& reading) const {
    return m * (reading * radps_per_unit - bias_radps);
  }
  /// The same with the specific force `f_mps2` sensed at that sample, for
  /// the g-sensitivity when it is modelled.
  Eigen::Vector3d Correct(const Eigen::Vector3d& reading,
                          const Eigen::Vector3d& f_mps2) const {
    Eigen::Vector3d b = bias_radps;
    if (g_sensitivity_radps_per_mps2) b += *g_sensitivity_radps_per_mps2 * f_mps2;
    return m * (reading * radps_per_unit - b);
  }
  /// 1σ of each entry of M (row-major 3×3); zero without a covariance.
  Eigen::Matrix3d MStd() const {
    Eigen::Matrix3d s = Eigen::Matrix3d::Zero();
    if (!m_covariance) return s;
    for (int i = 0; i < 9; ++i)
      s(i / 3, i % 3) = std::sqrt(std::max((*m_covariance)(i, i), 0.0));
    return s;
  }
  /// Largest change of the per-position bias over the session (rad/s, per
  /// axis): max − min.
  Eigen::Vector3d BiasChangeRadps() const {
    if (position_bias.empty()) return Eigen::Vector3d::Zero();
    Eigen::Vector3d lo = position_bias.front().bias_radps;
    Eigen::Vector3d hi = lo;
    for (const auto& b : position_bias) {
      lo = lo.cwiseMin(b.bias_radps);
      hi = hi.cwiseMax(b.bias_radps);
    }
    return hi - lo;
  }
};

}  // namespace mpcal
