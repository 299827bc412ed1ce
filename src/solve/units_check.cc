// Whether a log's readings fit their declared units: the evidence, gathered
// as the rows arrive, and the judgement (CheckUnits).
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

#include <fmt/format.h>

#include "mpcal/calibrate.h"
#include "mpcal/error.h"
#include "mpcal/gravity.h"
#include "mpcal/not_finite.h"
#include "mpcal/plausible.h"

namespace mpcal {
namespace {

// The band a magnitude at rest must fall in (kPlausibleRestRatioLow,
// kPlausibleRestRatioHigh) is plausible.h's, shared with inspection.
// At rest a gravity-free accelerometer reads its noise and bias, a few
// hundredths of g for a phone; with gravity in it, never less than half of g.
constexpr double kGravityRemovedRatio = 0.05;

// Rows between the magnitudes whose median is judged.
constexpr std::size_t kMagnitudeStride = 16;

// A log in rad/s that reaches beyond the largest full scale of MEMS
// gyroscopes (kMaxGyroRateRadps, plausible.h) holds deg/s (or counts).
constexpr double kMaxGyroRadps = kMaxGyroRateRadps;

void CheckGyroUnits(const UnitsEvidence& e) {
  if (e.gyro_units != GyroUnits::kRadps || !e.has_gyro) return;
  const double largest = e.largest_gyro;
  if (!(largest > kMaxGyroRadps)) return;
  const bool dps = largest * std::numbers::pi / 180.0 <= kMaxGyroRadps;
  throw Error(
      ErrorKind::kUnits,
      fmt::format("{}: the gyroscope reaches {:.4g} rad/s, beyond the {:.0f} rad/s "
                  "(4000 deg/s) full scale of MEMS gyroscopes; the readings look "
                  "like {}",
                  e.source,
                  largest,
                  kMaxGyroRadps,
                  dps ? "deg/s" : "raw ADC counts"),
      Advice{{{Option::kLogGyroUnits, dps ? "dps" : "counts"}}, Stage::kNone, ""});
}

}  // namespace

UnitsEvidence UnitsEvidence::Of(const RecordingView& recording) {
  UnitsEvidence e;
  e.Add(recording, 0, recording.size());
  return e;
}

void UnitsEvidence::Add(const RecordingView& part, std::size_t begin, std::size_t end) {
  if (end <= begin) return;
  if (rows == 0) {
    source = part.source;
    units = part.units;
    gyro_units = part.gyro_units;
    has_gyro = part.gyro_radps.size() == part.size();
  }
  // Every 16th row by its index in the log: a hand-held session is mostly
  // at rest, and during turns |a| stays near g as well.
  // A value that is NaN or infinite is refused here, the first read of a
  // calibration's rows (the rest of the accelerometer's and the time by
  // static detection's first pass): a view of the caller's memory may hold
  // what no log reader gives.
  for (std::size_t i = begin; i < end; ++i) {
    if ((rows + i - begin) % kMagnitudeStride != 0) continue;
    const double magnitude = part.accel[i].norm();
    if (!std::isfinite(magnitude)) RefuseNotFinite(part, RowColumn::kAccel, begin, i + 1);
    magnitudes.Add(magnitude);
  }
  if (has_gyro) {
    // (|x| <= max is false for NaN and infinities; tested without a branch
    // per row, so that the loop vectorises.)
    constexpr double kMax = std::numeric_limits<double>::max();
    bool finite = true;
    for (std::size_t i = begin; i < end; ++i) {
      const Eigen::Array3d w = part.gyro_radps[i].array().abs();
      finite &= (w <= kMax).all();
      largest_gyro = std::max(largest_gyro, w.maxCoeff());
    }
    if (!finite) RefuseNotFinite(part, RowColumn::kGyro, begin, end);
  }
  rows += end - begin;
}

std::string DescribeUnitsFinding(const UnitsError::Finding& f) {
  const std::string facts = fmt::format(
      "{}: the readings have a median magnitude of {:.4g} {}, but gravity is ",
      f.source,
      f.median_magnitude,
      UnitSymbol(f.units));
  if (f.units == AccelUnits::kMps2)
    return facts + fmt::format("{:.5g} m/s\u00b2", f.gravity_mps2);
  return facts + fmt::format("{:.4g} {} ({:.5g} m/s\u00b2)",
                             f.gravity_mps2 / *FixedMps2PerUnit(f.units),
                             UnitSymbol(f.units),
                             f.gravity_mps2);
}

void CheckUnits(const UnitsEvidence& e, double gravity_mps2) {
  CheckGyroUnits(e);
  if (!IsPlausibleGravity(gravity_mps2)) {
    throw Error(ErrorKind::kOption,
                fmt::format("gravity {} m/s2 is outside the plausible {}-{} m/s2",
                            gravity_mps2,
                            kMinGravityMps2,
                            kMaxGravityMps2),
                Advice{{{Option::kGravity, ""}}, Stage::kNone, ""});
  }
  if (e.rows == 0 || e.units == AccelUnits::kCounts) return;
  UnitsError::Finding f;
  f.source = e.source;
  f.units = e.units;
  f.gravity_mps2 = gravity_mps2;
  const double per_unit = *FixedMps2PerUnit(f.units);
  const double ratio = e.magnitudes.Quantile(0.5) * per_unit / gravity_mps2;
  if (ratio >= kPlausibleRestRatioLow && ratio <= kPlausibleRestRatioHigh) return;
  f.median_magnitude = ratio * gravity_mps2 / per_unit;
  Advice advice;
  std::string looks;
  if (f.units == AccelUnits::kMps2 && std::abs(f.median_magnitude - 1.0) < 0.5) {
    f.guess = UnitsGuess::kG;
    looks = "g";
  } else if (f.units == AccelUnits::kG &&
             std::abs(f.median_magnitude / kStandardGravityMps2 - 1.0) < 0.5) {
    f.guess = UnitsGuess::kMps2;
    looks = "m/s\u00b2";
  } else if (ratio * gravity_mps2 / kStandardGravityMps2 > 20.0) {
    f.guess = UnitsGuess::kCounts;
    looks = "raw ADC counts";
  } else if (ratio < kGravityRemovedRatio) {
    f.guess = UnitsGuess::kGravityRemoved;
    looks = "acceleration with gravity removed";
  }
  if (f.guess == UnitsGuess::kGravityRemoved) {
    // No unit or column mapping makes gravity-free readings calibratable.
  } else if (f.guess == UnitsGuess::kUnknown) {
    advice.settings = {{Option::kLogUnits, ""}, {Option::kLogColumns, ""}};
  } else {
    const AccelUnits guessed = f.guess == UnitsGuess::kG      ? AccelUnits::kG
                               : f.guess == UnitsGuess::kMps2 ? AccelUnits::kMps2
                                                              : AccelUnits::kCounts;
    advice.settings = {{Option::kLogUnits, std::string(ToString(guessed))}};
  }
  const std::string facts = DescribeUnitsFinding(f);
  throw UnitsError(f,
                   looks.empty() ? facts + "; check the units and the columns"
                                 : facts + "; the readings look like " + looks,
                   std::move(advice));
}

void CheckUnits(const RecordingView& recording, double gravity_mps2) {
  CheckUnits(UnitsEvidence::Of(recording), gravity_mps2);
}

}  // namespace mpcal
