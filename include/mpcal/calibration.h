/// \file calibration.h
/// \brief A calibration as stored in a calibration file: the estimated model,
/// its 1σ, the conditions it holds for (gravity, input units) and how well it
/// fit. Plain data; reading and writing the file is in calibration_file.h.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mpcal/model.h"
#include "mpcal/units.h"

namespace mpcal {

/// How the fit went, as recorded in the file (`"fit"`).
struct FitSummary {
  int positions = 0;
  double residual_rms_before_mps2 = 0.0;  ///< RMS of |a|−g over positions
  double residual_rms_after_mps2 = 0.0;
  int iterations = 0;
  bool converged = false;
  /// A-posteriori variance of unit weight (χ²/dof); ≈1 when the residuals
  /// are what the sensor noise explains.
  std::optional<double> variance_factor;
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
  ErrorModel model;
  /// 1σ of each parameter (same layout); nullopt when not estimated (truth).
  std::optional<ErrorModel> std;
  std::optional<FitSummary> fit;

  /// Specific force (m/s²) from a reading in `input_units`.
  Eigen::Vector3d Correct(const Eigen::Vector3d& reading) const {
    return model.Correct(reading * mps2_per_unit);
  }
};

}  // namespace mpcal
