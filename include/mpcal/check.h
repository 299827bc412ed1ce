/// \file check.h
/// \brief A result's checks, each judged: whether the result can be used as
/// it is, deserves a look, or must not be used, with the finding and the
/// figures behind it. Calibrations are judged in mpcal/verdict.h,
/// verifications in mpcal/verify.h; the words belong to the caller.
#pragma once

#include <string_view>
#include <vector>

namespace mpcal {

enum class Verdict {
  kGood,      ///< nothing to do
  kLookAt,    ///< usable, but the finding deserves a look
  kDoNotUse,  ///< the result (or this part of it) is not to be used
};
/// "good", "look at", "do not use".
std::string_view ToString(Verdict verdict);

enum class CheckKind {
  kFit,         ///< the residuals against the sensor noise, outliers
  kPositions,   ///< enough positions, spanning the sphere
  kBiasDrift,   ///< the bias constant over the session or not
  kSplitHalf,   ///< the halves of the session agree: the 1σ are honest
  kUnits,       ///< the readings' units and nominal scale
  kGyroscope,   ///< the gyroscope's turns fit, or why it was not calibrated
  kCorrection,  ///< verification: the corrected walk against the raw one
  kClock,       ///< verification: the IMU's and the reference's clocks
  kStops,       ///< verification: stops for zero-velocity updates
};
/// "fit", "positions", "bias drift", "split-half", "units", "gyroscope",
/// "correction", "clock", "stops".
std::string_view ToString(CheckKind kind);

/// What a check found; `Check::value`, `limit` and `count` hold its figures
/// as each comment says.
enum class CheckFinding {
  kFitNotConverged,        ///< the solver did not converge
  kFitWithinNoise,         ///< value: variance factor; limit: its χ² test's p
  kFitBeyondNoise,         ///< value: variance factor; limit: p below the significance
  kOutliersExcluded,       ///< count: positions excluded; value: variance factor
  kPositionsEnough,        ///< count: positions used; value: degrees of freedom
  kPositionsNoRedundancy,  ///< count: positions used (as many as the parameters)
  kPoorlyDetermined,       ///< count: parameters poorly determined
                           ///< (SolveResult::poorly_determined)
  kDriftNotSignificant,    ///< value: p; limit: the significance
  kDriftFitted,            ///< value: p; limit: the significance
  kDriftNotTested,         ///< too few positions for the drift's three parameters
  kSplitConsistent,        ///< value: the smallest p; limit: the per-split significance
  kSplitDisagree,  ///< value: the smallest p; limit: the per-split significance; count:
                   ///< splits that disagree
  kSplitNotPossible,      ///< no split determines every parameter in both halves
  kUnitsFixed,            ///< the readings' magnitude fits their declared units
  kUnitsCounts,           ///< raw counts; value: counts per g of the nominal scale
  kGyroConverged,         ///< value: tilt RMS after (rad); limit: variance factor
  kGyroPoorlyDetermined,  ///< count: entries of M; value: largest 1σ; limit: the
                          ///< threshold
  kGyroNotCalibrated,   ///< too few turns or undetermined entries (GyroResult::findings)
  kGyroNotConverged,    ///< the gyroscope's solver did not converge
  kCorrectedCloser,     ///< value: corrected horizontal RMS to the reference (m);
                        ///< limit: the raw one's (m)
  kCorrectedNotCloser,  ///< value, limit: as kCorrectedCloser
  kNoCalibration,       ///< no calibration given: only the raw walk
  kClockAgrees,         ///< value: the offset used (s)
  kClockDisagrees,      ///< value: the offset the start of motion suggests (s);
                        ///< limit: the offset used (s)
  kStopsFound,          ///< count: still stretches, the end rests included
  kNoStop,              ///< no zero-velocity update between the end rests
  kWalkGyroUsed,        ///< the attitude followed by the gyroscope
  kWalkGyroUnused,      ///< the log has a gyroscope the options left out
  kWalkNoGyro,          ///< no gyroscope: attitude fixed after the start
};

struct Check {
  CheckKind kind = CheckKind::kFit;
  Verdict verdict = Verdict::kGood;
  CheckFinding finding = CheckFinding::kFitWithinNoise;
  double value = 0.0;
  double limit = 0.0;
  int count = 0;
};

/// The worst verdict of `checks` (kGood for none).
Verdict Worst(const std::vector<Check>& checks);

}  // namespace mpcal
