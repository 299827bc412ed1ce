/// \file calibration.h
/// \brief A calibration as stored in a calibration file: the estimated model,
/// its 1σ, the conditions it holds for (gravity, input units) and how well it
/// fit. Plain data; reading and writing the file is in calibration_file.h.
#pragma once

#include <optional>
#include <string>
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
  std::optional<FitSummary> fit;
  /// Per-position detail; empty for a truth file.
  std::vector<PositionSummary> positions;
  /// Warnings the user should see with the calibration (poorly determined
  /// parameters, excluded positions, ...).
  std::vector<std::string> warnings;
  std::optional<Provenance> provenance;
  /// The gyroscope of the same IMU, when the log had one (an IMU file,
  /// format mpcal.imu/1); nullopt for an accelerometer-only calibration.
  std::optional<GyroCalibration> gyroscope;

  /// Specific force (m/s²) from a reading in `input_units`.
  Eigen::Vector3d Correct(const Eigen::Vector3d& reading) const {
    return model.Correct(reading * mps2_per_unit);
  }
};

}  // namespace mpcal
