/// \file calibrate.h
/// \brief A whole calibration from a recording: detect the static positions,
/// turn their means into m/s² (finding the nominal scale of raw counts),
/// initialise, solve, and package the result as a Calibration.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "mpcal/calibration.h"
#include "mpcal/detect.h"
#include "mpcal/gyro.h"
#include "mpcal/recording.h"
#include "mpcal/solve.h"

namespace mpcal {

struct CalibrateOptions {
  DetectOptions detect;
  SolveOptions solve;
  /// Raw counts only: the datasheet's sensitivity (counts per g, e.g. 16384
  /// for an MPU-6050 at ±2 g). 0: the nominal scale is the radius of the
  /// sphere the positions lie on. With it, the scale-factor errors (ppm) and
  /// biases are relative to the datasheet; the file records which
  /// (Calibration::scale_reference).
  double counts_per_g = 0.0;
  /// The gyroscope, when the recording has one (gyro.h).
  GyroOptions gyro;
  /// Calibrate the gyroscope too when the recording has gyroscope readings.
  bool calibrate_gyroscope = true;
  std::string Validate() const;
};

struct CalibrateResult {
  DetectResult detection;
  /// The positions given to the solver (m/s²), in detection order.
  std::vector<PositionObservation> positions;
  /// Factor applied to the recording's units to get nominal m/s².
  double mps2_per_unit = 1.0;
  SolveResult solve;
  /// The gyroscope's fit, when the recording has one and the accelerometer
  /// converged. calibration.gyroscope is set only when it converged.
  std::optional<GyroResult> gyro;
  /// What goes into the calibration file.
  Calibration calibration;
  std::vector<std::string> warnings;
};

/// Catches a log in one unit read as another from the magnitude of its
/// readings, before detection (read in the wrong unit, the noise at rest looks
/// ten times too large or too small and detection would fail for the wrong
/// reason). Raw counts and an empty recording pass: counts have no fixed scale.
/// \throws mpcal::Error when the median magnitude is far from `gravity_mps2`
///   (outside 0.5-1.6 g, beyond any sensor's own errors), saying which
///   `--units` the readings look like.
void CheckUnits(const Recording& recording, double gravity_mps2);

/// \throws mpcal::Error when the recording has too few static positions for
///   the model (the message says how many were found and what to record), or
///   when the positions leave a parameter undetermined, or invalid options.
CalibrateResult CalibrateRecording(const Recording& recording,
                                   const CalibrateOptions& options);

}  // namespace mpcal
