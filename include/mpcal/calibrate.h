/// \file calibrate.h
/// \brief A whole calibration from a recording: detect the static positions,
/// turn their means into m/s² (finding the nominal scale of raw counts),
/// initialise, solve, and package the result as a Calibration.
#pragma once

#include <optional>
#include <span>
#include <string>
#include <utility>
#include <vector>

#include "mpcal/calibration.h"
#include "mpcal/coverage.h"
#include "mpcal/detect.h"
#include "mpcal/error.h"
#include "mpcal/gyro.h"
#include "mpcal/recording.h"
#include "mpcal/recording_view.h"
#include "mpcal/solve.h"
#include "mpcal/systematic_sample.h"

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

/// What the magnitude of the readings says about their units.
enum class UnitsGuess {
  kUnknown,  ///< none of the units fits: the columns or units are wrong
  kG,        ///< read as m/s², the readings are about 1: they are in g
  kMps2,     ///< read as g, the readings are about 9.8: they are in m/s²
  kCounts,   ///< far beyond any g: raw ADC counts
  /// Below a twentieth of g whatever the units: acceleration with gravity
  /// removed (a phone's "linear" or "user" acceleration), which holds no
  /// gravity to calibrate against.
  kGravityRemoved,
};

/// The readings do not fit their declared units (thrown by CheckUnits):
/// kind kUnits; the advice is the units they look like (Option::kLogUnits),
/// or the units and the columns to check.
class UnitsError : public Error {
 public:
  struct Finding {
    std::string source;
    AccelUnits units = AccelUnits::kMps2;
    double median_magnitude = 0.0;  ///< in `units`
    double gravity_mps2 = 0.0;
    UnitsGuess guess = UnitsGuess::kUnknown;
  };
  UnitsError(Finding finding, const std::string& what, Advice advice)
      : Error(ErrorKind::kUnits, what, std::move(advice)), finding_(std::move(finding)) {}
  const Finding& finding() const { return finding_; }

 private:
  Finding finding_;
};

/// The finding as facts in one unit spelling: "a.csv: the readings have a
/// median magnitude of 259.7 m/s², but gravity is 9.8066 m/s²" (for a log in
/// g: "... 9.6 g, but gravity is 1.000 g (9.8066 m/s²)").
std::string DescribeUnitsFinding(const UnitsError::Finding& finding);

/// Why a session cannot be calibrated (thrown by CalibrateRecording): kind
/// kSession, with the detection or coverage behind it.
enum class SessionProblem {
  kNoPositions,      ///< detection found none: detection.finding says why
  kTooFewPositions,  ///< fewer than the model's parameters: see coverage
  kCountsNotSpread,  ///< raw counts whose positions do not span the sphere
};

class SessionError : public Error {
 public:
  SessionError(SessionProblem problem,
               std::string source,
               DetectResult detection,
               CoverageResult coverage,
               const std::string& what,
               Advice advice)
      : Error(ErrorKind::kSession, what, std::move(advice)),
        problem_(problem),
        source_(std::move(source)),
        detection_(std::move(detection)),
        coverage_(std::move(coverage)) {}
  SessionProblem problem() const { return problem_; }
  const std::string& source() const { return source_; }
  const DetectResult& detection() const { return detection_; }
  /// kTooFewPositions only.
  const CoverageResult& coverage() const { return coverage_; }

 private:
  SessionProblem problem_;
  std::string source_;
  DetectResult detection_;
  CoverageResult coverage_;
};

/// What CheckUnits judges a log's units by, gathered as its rows arrive
/// (Add) or from a whole recording (Of): the magnitudes of every 16th
/// accelerometer reading (a SystematicSample, for their median) and the
/// gyroscope's largest reading.
struct UnitsEvidence {
  std::string source;
  AccelUnits units = AccelUnits::kMps2;
  GyroUnits gyro_units = GyroUnits::kRadps;
  bool has_gyro = false;
  std::size_t rows = 0;
  SystematicSample magnitudes;
  double largest_gyro = 0.0;  ///< max |ω| over axes and rows, the log's unit

  static UnitsEvidence Of(const RecordingView& recording);
  /// Rows [begin, end) of `part` (the first call sets source and units).
  /// \throws NotFiniteError for a gyroscope reading, or an accelerometer
  ///   reading of those sampled, that is NaN or infinite.
  void Add(const RecordingView& part, std::size_t begin, std::size_t end);
};

/// Catches a log in one unit read as another from the magnitude of its
/// readings, before detection (read in the wrong unit, the noise at rest looks
/// ten times too large or too small and detection would fail for the wrong
/// reason). Raw counts and an empty recording pass: counts have no fixed scale.
/// \throws mpcal::UnitsError when the median magnitude is far from
///   `gravity_mps2` (outside 0.5-1.6 g, beyond any sensor's own errors),
///   saying which units the readings look like; mpcal::Error (kOption) when
///   `gravity_mps2` is not a plausible gravity; mpcal::Error (kUnits, with
///   the gyroscope's units in its Advice) when a gyroscope read in rad/s
///   reaches beyond 70 rad/s (4000 deg/s, the largest full scale of MEMS
///   gyroscopes): deg/s, or raw counts, read as rad/s.
void CheckUnits(const UnitsEvidence& evidence, double gravity_mps2);
/// CheckUnits on the evidence of a whole recording.
void CheckUnits(const RecordingView& recording, double gravity_mps2);

/// The turns between neighbouring positions (in time order, as DetectStatic
/// found them, grown to the motion by ExtendToMotion), integrated from the
/// gyroscope's readings by the exponential
/// map with the bias measured at rest (the mean of the two positions' mean
/// readings) taken out. The nominal scale is that of the gyroscope's units;
/// for raw counts, the one common scale that carries the gravity direction
/// of each position onto the next best (the tilt's least squares over a log
/// grid, refined by golden section), so that angles come out in degrees.
/// Returns `scale_radps_per_unit` too when asked. Empty when the recording
/// has no gyroscope or fewer than two positions.
/// \throws mpcal::Error (kInput) when an interval lies outside the recording.
std::vector<Turn> MeasureTurns(const RecordingView& recording,
                               std::span<const StaticInterval> intervals,
                               double* scale_radps_per_unit = nullptr);

/// \throws mpcal::SessionError when the recording has no static position, too
///   few for the model (with the coverage: how many, what to record), or raw
///   counts whose positions do not give their scale; mpcal::UnitsError as
///   CheckUnits; mpcal::Error for invalid options.
CalibrateResult CalibrateRecording(const RecordingView& recording,
                                   const CalibrateOptions& options);

}  // namespace mpcal
