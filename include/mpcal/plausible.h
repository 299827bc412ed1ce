/// \file plausible.h
/// \brief What is physically plausible, stated once: the ranges every reader
/// and every option check tests values against.
///
/// A value outside these ranges is not a poor sensor but a corrupt line, a
/// wrong unit or a file that is not what it claims; mpcal refuses it rather
/// than compute with it (a bias of 1e308 m/s² would otherwise be applied).
#pragma once

#include <cmath>

#include "mpcal/gravity.h"
#include "mpcal/units.h"

namespace mpcal {

/// Gravity's plausible range (kMinGravityMps2, kMaxGravityMps2,
/// IsPlausibleGravity) is stated once, in gravity.h.

/// The largest acceleration any accelerometer reports: shock sensors reach a
/// few thousand g; 10,000 g leaves margin. A reading beyond it, in the
/// log's declared units, is a corrupt value or the wrong unit.
inline constexpr double kMaxReadingG = 1e4;
/// The largest raw reading: a signed 32-bit ADC output.
inline constexpr double kMaxReadingCounts = 2147483648.0;
/// kMaxReadingG (or kMaxReadingCounts) expressed in `units`.
inline double MaxReading(AccelUnits units) {
  switch (units) {
    case AccelUnits::kMps2:
      return kMaxReadingG * kStandardGravityMps2;
    case AccelUnits::kG:
      return kMaxReadingG;
    case AccelUnits::kCounts:
      return kMaxReadingCounts;
  }
  return kMaxReadingCounts;
}

/// The largest time stamp in seconds: about 31,700 years, beyond any
/// logger's clock (Unix time is 1.8e9 s; in ms read as seconds, 1.8e12).
inline constexpr double kMaxTimeS = 1e12;

/// The shortest plausible sample period: the fastest MEMS inertial sensors
/// sample at a few tens of kHz (gyroscopes up to 32 kHz, vibration
/// accelerometers up to 100 kHz); 1 MHz leaves margin. A log whose typical
/// time step is shorter holds a time column in another unit than it is read
/// in (ns read as s), or no time at all; every rate derived from it (window
/// lengths, thresholds) would be meaningless.
inline constexpr double kMinSamplePeriodS = 1e-6;
inline constexpr double kMaxSampleRateHz = 1.0 / kMinSamplePeriodS;

/// A calibration's parameters, in SI: a bias beyond 10 g is not an
/// accelerometer's (consumer parts: below 1 g); a scale-factor error beyond
/// ±0.5 (50 %) and a non-orthogonality angle of π/4 (45°) or more are not a
/// sensor's but a broken fit or a corrupt file.
inline constexpr double kMaxBiasMps2 = 10.0 * kStandardGravityMps2;
inline constexpr double kMaxScaleFactorError = 0.5;
inline constexpr double kMaxNonOrthogonalityRad = 0.7853981633974483;
/// The largest magnitude of the `index`th packed parameter (the order of
/// kParameterNames in model.h): kMaxBiasMps2, kMaxScaleFactorError or
/// kMaxNonOrthogonalityRad.
inline constexpr double MaxParameterMagnitude(int index) {
  if (index < 3) return kMaxBiasMps2;
  if (index < 6) return kMaxScaleFactorError;
  return kMaxNonOrthogonalityRad;
}

/// Counts per g of a raw-counts calibration: 1 (a float "count") to 2^31.
inline constexpr double kMinCountsPerG = 1e-3;
inline constexpr double kMaxCountsPerG = 2147483648.0;

/// The magnitude of an accelerometer at rest, in m/s², may differ from
/// gravity by the sensor's own errors (consumer parts: up to ~0.5 g of bias
/// and 10 % of scale): as a fraction of gravity, outside [0.5, 1.6] the
/// units are wrong, not the sensor.
inline constexpr double kPlausibleRestRatioLow = 0.5;
inline constexpr double kPlausibleRestRatioHigh = 1.6;

/// The largest angular rate any MEMS gyroscope reports: 4000 °/s full scale
/// (about 70 rad/s). A reading in rad/s beyond it holds deg/s or counts.
inline constexpr double kMaxGyroRateRadps = 4000.0 * 0.017453292519943295;
/// A gyroscope's calibration (gyro_calibration.h), ω = M (r·k − b − G f):
/// - its bias b cannot exceed the full scale it is measured on (4000 °/s):
///   consumer parts stay within a few °/s, and a bias beyond full scale is a
///   deg/s log read as rad/s or a corrupt file; for raw counts b is the ADC's
///   offset, within kMaxReadingCounts counts;
/// - M's diagonal is a scale 1 + s with |s| < kMaxScaleFactorError, as for
///   the accelerometer (relative to the nominal scale k);
/// - its off-diagonal terms are small angles (misalignment of the triad and
///   its rotation against the accelerometer's, rad): beyond 0.5 the two
///   triads are not mounted together, or the fit diverged;
/// - a 1σ of M beyond kMaxScaleFactorError says nothing about the sensor;
/// - the bias's g-sensitivity G: datasheets give 0.01-0.1 °/s per g, the
///   worst parts below 1; 10 °/s per g (0.0178 rad/s per m/s²) leaves margin.
inline constexpr double kMaxGyroBiasRadps = kMaxGyroRateRadps;
inline constexpr double kMaxGyroMisalignment = 0.5;
inline constexpr double kMaxGyroGSensitivityRadpsPerMps2 =
    10.0 * 0.017453292519943295 / kStandardGravityMps2;
/// Counts per rad/s of a raw-counts gyroscope: 1e-3 (a float "count") to
/// 2^31, as for the accelerometer (kMinCountsPerG, kMaxCountsPerG).
inline constexpr double kMinCountsPerRadps = 1e-3;
inline constexpr double kMaxCountsPerRadps = 2147483648.0;
/// The longest sample period a calibration file may record (s): one hour
/// (the shortest is kMinSamplePeriodS above).
inline constexpr double kMaxSamplePeriodS = 3600.0;

}  // namespace mpcal
