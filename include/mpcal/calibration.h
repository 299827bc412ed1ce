/// \file calibration.h
/// \brief A calibration as stored in a calibration file: the estimated model,
/// its 1σ, the conditions it holds for (gravity, input units) and how well it
/// fit. Plain data; reading and writing the file is in calibration_file.h.
#pragma once

#include <algorithm>
#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "mpcal/gyro_calibration.h"
#include "mpcal/model.h"
#include "mpcal/units.h"

namespace mpcal {

/// One static position as the fit saw it (`"positions"` in the file), so
/// that a calibration file alone is enough to judge and plot the fit.
struct PositionSummary {
  double start_s = 0.0;  ///< in the log's own clock
  double end_s = 0.0;
  std::size_t samples = 0;
  /// Mean reading scaled to nominal m/s² (reading × mps2_per_unit).
  Eigen::Vector3d mean_mps2 = Eigen::Vector3d::Zero();
  Eigen::Vector3d sample_std_mps2 = Eigen::Vector3d::Zero();
  /// |a| − g with the raw reading (nominal scale only) and corrected (m/s²).
  double residual_before_mps2 = 0.0;
  double residual_after_mps2 = 0.0;
  /// Residual predicted by a fit without this position (m/s²).
  std::optional<double> cross_validation_residual_mps2;
  /// False when the position was excluded from the fit (outlier).
  bool used = true;
};

/// Where a calibration came from, so that a report can be reproduced.
struct Provenance {
  std::string mpcal_version;
  std::string input;    ///< the log's path, as given
  std::string options;  ///< the options that mattered, as a command line
};

/// A bias that drifts linearly in time over the calibration session (a
/// sensor warming up after power-on): b(t) = bias_mps2 + d·(t − t_ref). The
/// calibration's bias_mps2 is the bias at t_ref, the middle of the session's
/// positions (the mean of their middles): the session's average bias, which
/// a correction that ignores the drift (apply) uses, and the one a constant
/// fit would find.
struct BiasDrift {
  /// d (m/s² per second) and its 1σ.
  Eigen::Vector3d mps2_per_s = Eigen::Vector3d::Zero();
  Eigen::Vector3d std_mps2_per_s = Eigen::Vector3d::Zero();
  /// t_ref in the calibration log's own clock (s).
  double reference_time_s = 0.0;
  /// P-value of the test that chose the drift over a constant bias (a
  /// likelihood ratio with the sensor noise as weights, or an F test when the
  /// positions scatter beyond it; SolveOptions::consider_bias_drift).
  double p_value = 0.0;
};

/// How the positions were split in two for the split-half check.
enum class SplitKind { kByTime, kInterleaved };
/// "by_time", "interleaved": the keys in the file.
inline std::string_view ToString(SplitKind kind) {
  return kind == SplitKind::kByTime ? "by_time" : "interleaved";
}

/// Positions beyond the parameters each half of a split needs: 5 by time (a
/// half estimates its own scatter of the positions), 3 interleaved (the
/// halves share the whole session's orientations and take its scatter).
inline int SplitRedundancyNeeded(SplitKind kind) {
  return kind == SplitKind::kByTime ? 5 : 3;
}

/// One split of the used positions into two halves, each calibrated alone,
/// and how far the two estimates differ in units of their combined 1σ:
/// z = (p₁ − p₂)/√(σ₁² + σ₂²), standard normal when the 1σ are honest
/// (docs/method.md §9).
struct SplitHalfComparison {
  SplitKind kind = SplitKind::kByTime;
  int positions_first = 0;
  int positions_second = 0;
  /// False when a half has fewer than SplitRedundancyNeeded(kind) positions
  /// more than the parameters, does not determine every parameter (or its
  /// fit failed): then there is no z.
  bool determined = false;
  /// Per estimated parameter, in the packed order of kParameterNames.
  std::vector<double> z;
  /// √(mean z²): about 1 ± 0.24 for 9 honest parameters.
  double rms_z = 0.0;
  /// dᵀ(C₁ + C₂)⁻¹d of the difference d with the halves' covariances, χ²
  /// with one degree of freedom per parameter when the 1σ are honest, and
  /// its upper-tail probability.
  double chi2 = 0.0;
  int dof = 0;
  double p_value = 1.0;
  /// p_value below its share of the check's significance (the significance
  /// over the number of determined splits): the halves disagree beyond
  /// chance.
  bool disagree = false;
};

/// The significance each determined split of a check is tested at: the
/// check's `significance` shared among them (Bonferroni), so that it stays
/// the rate at which a session with honest 1σ has any split disagree.
inline double PerSplitSignificance(const std::vector<SplitHalfComparison>& comparisons,
                                   double significance) {
  const auto determined = std::count_if(
      comparisons.begin(), comparisons.end(), [](const auto& c) { return c.determined; });
  return significance / static_cast<double>(std::max<std::ptrdiff_t>(determined, 1));
}

/// The split-half check of one calibration (`"fit.split_half"`).
struct SplitHalfSummary {
  /// The check's false-alarm rate: the probability that a session whose 1σ
  /// is honest has any split called disagreeing.
  double significance = 0.01;
  std::vector<SplitHalfComparison> comparisons;
  /// Factor every 1σ was multiplied by: 1, or √(χ²/dof) of the worst split
  /// whose halves disagree beyond chance.
  double widening = 1.0;
};

/// How the fit went, as recorded in the file (`"fit"`).
struct FitSummary {
  int positions = 0;
  double residual_rms_before_mps2 = 0.0;  ///< RMS of |a|−g over positions
  double residual_rms_after_mps2 = 0.0;
  int iterations = 0;
  bool converged = false;
  /// Positions excluded as outliers (not counted in `positions`).
  int excluded_positions = 0;
  /// A-posteriori variance of unit weight (χ²/dof); ≈1 when the residuals
  /// are what the sensor noise explains.
  std::optional<double> variance_factor;
  /// Scatter of the positions beyond what the sensor noise explains (m/s²,
  /// 1σ): hand tremor, non-white noise or model error. 0 when the noise
  /// explains the residuals.
  std::optional<double> position_scatter_mps2;
  /// Leave-one-position-out RMS of predicted residuals (m/s²).
  std::optional<double> cross_validation_rms_mps2;
  /// The two halves of the session calibrated alone and compared.
  std::optional<SplitHalfSummary> split_half;
};

struct Calibration {
  ModelKind model_kind = ModelKind::kShinElSheimy9;
  /// The gravity magnitude the calibration was made against (m/s²).
  double gravity_mps2 = 9.80665;
  /// Units of the logs this calibration applies to, and the nominal factor
  /// that turns them into m/s² before the model is applied.
  AccelUnits input_units = AccelUnits::kMps2;
  double mps2_per_unit = 1.0;
  /// Raw counts only: where mps2_per_unit comes from, "fitted_sphere" (the
  /// radius of the sphere the positions lie on: scale-factor errors are
  /// relative to it) or "datasheet" (a given counts per g: they are relative
  /// to the datasheet's sensitivity). Empty for fixed units.
  std::string scale_reference;
  /// How the log it was made from was read, so that logs of the same logger
  /// are read alike: the column mapping ("t=millis,ax=ax,ay=ay,az=az"), the
  /// time unit ("s", "ms", "us", "ns", "index") and, for a sample index, the
  /// rate (Hz). Absent in files written before it was recorded.
  struct InputLayout {
    std::string columns;
    std::string time_unit;
    double rate_hz = 0.0;
  };
  std::optional<InputLayout> input_layout;
  ErrorModel model;
  /// 1σ of each parameter (same layout); nullopt when not estimated (truth).
  std::optional<ErrorModel> std;
  /// Present when the session showed a significant bias drift.
  std::optional<BiasDrift> bias_drift;
  std::optional<FitSummary> fit;
  /// Per-position detail; empty for a truth file.
  std::vector<PositionSummary> positions;
  /// Warnings the user should see with the calibration (poorly determined
  /// parameters, excluded positions, ...).
  std::vector<std::string> warnings;
  std::optional<Provenance> provenance;
  /// The other tool's file this calibration was read from ("imu_tk .calib")
  /// by an import; such a calibration has no 1σ (`std` and the gyroscope's
  /// bias_std_radps and m_covariance are nullopt), and no fit or positions.
  std::optional<std::string> imported_from;
  /// The gyroscope of the same IMU, when the log had one (an IMU file,
  /// format mpcal.imu/1); nullopt for an accelerometer-only calibration.
  std::optional<GyroCalibration> gyroscope;

  /// Specific force (m/s²) from a reading in `input_units`.
  Eigen::Vector3d Correct(const Eigen::Vector3d& reading) const {
    return model.Correct(reading * mps2_per_unit);
  }

  /// The same correction as the affine map it is, a = linear · reading +
  /// offset (model.h: T·diag(1/(1 + s))·(u y − b)), for loops over many
  /// samples: Correct evaluates T's tangents and cosines at every call.
  struct AffineCorrection {
    Eigen::Matrix3d linear;
    Eigen::Vector3d offset;
    Eigen::Vector3d operator()(const Eigen::Vector3d& reading) const {
      return linear * reading + offset;
    }
  };
  AffineCorrection Affine() const {
    const Eigen::Matrix3d t_over_scale =
        model.NonOrthogonality() *
        (Eigen::Vector3d::Ones() + model.scale_factor_error).cwiseInverse().asDiagonal();
    return {t_over_scale * mps2_per_unit, -t_over_scale * model.bias_mps2};
  }
};

}  // namespace mpcal
