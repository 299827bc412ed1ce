// A whole calibration from a recording: detection, units, solve, packaging.
#include "mpcal/calibrate.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <fmt/format.h>

#include "mpcal/coverage.h"
#include "mpcal/error.h"
#include "mpcal/plausible.h"

namespace mpcal {
namespace {

// The magnitude of a static mean in m/s² may differ from g by the sensor's
// own errors (consumer parts: up to ~0.5 g of bias and 10 % of scale); far
// outside this band the units are wrong, not the sensor.
constexpr double kPlausibleRestRatioLow = 0.5;
constexpr double kPlausibleRestRatioHigh = 1.6;

// Median magnitude of the readings, on every 16th sample: a hand-held
// session is mostly at rest, and during turns |a| stays near g as well.
double MedianMagnitude(const Recording& recording) {
  constexpr std::size_t kStride = 16;
  std::vector<double> m;
  m.reserve(recording.size() / kStride + 1);
  for (std::size_t i = 0; i < recording.size(); i += kStride)
    m.push_back(recording.accel[i].norm());
  std::nth_element(m.begin(), m.begin() + m.size() / 2, m.end());
  return m[m.size() / 2];
}

}  // namespace

void CheckUnits(const Recording& recording, double gravity_mps2) {
  if (recording.empty() || recording.units == AccelUnits::kCounts) return;
  const AccelUnits units = recording.units;
  const std::string& source = recording.source;
  const double ratio =
      MedianMagnitude(recording) * *FixedMps2PerUnit(units) / gravity_mps2;
  if (ratio >= kPlausibleRestRatioLow && ratio <= kPlausibleRestRatioHigh) return;
  const double as_read = ratio * gravity_mps2 / *FixedMps2PerUnit(units);
  std::string hint = "check --units and --columns";
  const double g_if_mps2 = ratio * gravity_mps2 / kStandardGravityMps2;
  if (units == AccelUnits::kMps2 && std::abs(as_read - 1.0) < 0.5) {
    hint = "the readings look like g: add --units g";
  } else if (units == AccelUnits::kG &&
             std::abs(as_read / kStandardGravityMps2 - 1.0) < 0.5) {
    hint = "the readings look like m/s2: use --units mps2";
  } else if (g_if_mps2 > 20.0) {
    hint = "the readings look like raw ADC counts: add --units counts";
  }
  throw Error(fmt::format(
      "{}: the readings have a median magnitude of {:.4g} {}, but gravity is {:.5g} m/s2 "
      "({:.4g} {}); {}",
      source,
      as_read,
      ToString(units),
      gravity_mps2,
      gravity_mps2 / *FixedMps2PerUnit(units),
      ToString(units),
      hint));
}

std::string CalibrateOptions::Validate() const {
  if (counts_per_g != 0.0 &&
      !(counts_per_g >= kMinCountsPerG && counts_per_g <= kMaxCountsPerG)) {
    return fmt::format(
        "counts_per_g = {} is not a sensitivity ({:g} to {:g} counts per g)",
        counts_per_g,
        kMinCountsPerG,
        kMaxCountsPerG);
  }
  if (std::string p = detect.Validate(); !p.empty()) return "detect: " + p;
  if (std::string p = solve.Validate(); !p.empty()) return "solve: " + p;
  if (std::string p = gyro.Validate(); !p.empty()) return "gyro: " + p;
  return "";
}

CalibrateResult CalibrateRecording(const Recording& recording,
                                   const CalibrateOptions& options) {
  if (const std::string problem = options.Validate(); !problem.empty()) {
    throw Error("calibration options: " + problem);
  }
  CalibrateResult result;
  CheckUnits(recording, options.solve.gravity_mps2);
  result.detection = DetectStatic(recording, options.detect);
  const auto& intervals = result.detection.intervals;
  if (intervals.empty()) throw Error(result.detection.message);
  const int needed = ParameterCount(options.solve.model);
  if (static_cast<int>(intervals.size()) < needed) {
    CoverageOptions coverage;
    coverage.model = options.solve.model;
    coverage.units = recording.units;
    throw Error(fmt::format("{}: {}; run 'mpcal detect {}' to see the positions found",
                            recording.source,
                            AssessCoverage(result.detection, coverage).summary,
                            recording.source));
  }

  // Raw counts: the nominal scale is the radius of the sphere the position
  // means lie on, so that the model's scale-factor errors stay small numbers
  // and the six-position initialisation works as for any other unit.
  Eigen::Vector3d nominal_offset_mps2 = Eigen::Vector3d::Zero();
  if (const auto fixed = FixedMps2PerUnit(recording.units)) {
    result.mps2_per_unit = *fixed;
  } else {
    std::vector<Eigen::Vector3d> means;
    for (const auto& in : intervals) means.push_back(in.mean);
    const SphereFit sphere = FitSphere(means, AccelUnits::kCounts);
    if (!sphere.fitted || !(sphere.radius > 0.0)) {
      throw Error(fmt::format(
          "{}: the {} static positions do not spread over the sphere, so the offset and "
          "scale of the raw counts cannot be found from them; record positions with each "
          "axis up and down (run 'mpcal detect {} --units counts')",
          recording.source,
          intervals.size(),
          recording.source));
    }
    result.mps2_per_unit = options.counts_per_g > 0.0
                               ? kStandardGravityMps2 / options.counts_per_g
                               : options.solve.gravity_mps2 / sphere.radius;
    nominal_offset_mps2 = sphere.centre * result.mps2_per_unit;
  }

  for (const auto& in : intervals) {
    PositionObservation p;
    p.mean_mps2 = in.mean * result.mps2_per_unit;
    p.sample_std_mps2 = in.std * result.mps2_per_unit;
    p.samples = in.samples();
    p.start_s = in.start_s;
    p.end_s = in.end_s;
    result.positions.push_back(p);
  }

  SolveOptions solve = options.solve;
  solve.nominal_offset_mps2 = nominal_offset_mps2;
  result.solve = Solve(result.positions, solve);
  result.warnings = result.detection.warnings;  // positions dropped for clipping
  result.warnings.insert(
      result.warnings.end(), result.solve.warnings.begin(), result.solve.warnings.end());

  Calibration& c = result.calibration;
  c.model_kind = options.solve.model;
  c.gravity_mps2 = options.solve.gravity_mps2;
  c.input_units = recording.units;
  c.mps2_per_unit = result.mps2_per_unit;
  if (recording.units == AccelUnits::kCounts) {
    c.scale_reference = options.counts_per_g > 0.0 ? "datasheet" : "fitted_sphere";
  }
  c.model = result.solve.estimate;
  c.std = result.solve.std;
  c.bias_drift = result.solve.bias_drift;
  FitSummary fit;
  fit.positions = static_cast<int>(result.positions.size());
  fit.residual_rms_before_mps2 = result.solve.residual_rms_before_mps2;
  fit.residual_rms_after_mps2 = result.solve.residual_rms_after_mps2;
  fit.iterations = result.solve.iterations;
  fit.converged = result.solve.converged();
  fit.variance_factor = result.solve.variance_factor;
  fit.position_scatter_mps2 = result.solve.position_scatter_mps2;
  fit.excluded_positions = static_cast<int>(
      std::count(result.solve.used.begin(), result.solve.used.end(), false));
  fit.positions -= fit.excluded_positions;
  if (!result.solve.cross_validation_residual_mps2.empty()) {
    fit.cross_validation_rms_mps2 = result.solve.cross_validation_rms_mps2;
  }
  fit.split_half = result.solve.split_half;
  c.fit = fit;
  for (std::size_t k = 0; k < result.positions.size(); ++k) {
    PositionSummary s;
    s.start_s = result.positions[k].start_s;
    s.end_s = result.positions[k].end_s;
    s.samples = result.positions[k].samples;
    s.mean_mps2 = result.positions[k].mean_mps2;
    s.sample_std_mps2 = result.positions[k].sample_std_mps2;
    s.residual_before_mps2 = result.solve.residual_before_mps2[k];
    s.residual_after_mps2 = result.solve.residual_after_mps2[k];
    s.used = result.solve.used[k];
    if (!result.solve.cross_validation_residual_mps2.empty() &&
        std::isfinite(result.solve.cross_validation_residual_mps2[k])) {
      s.cross_validation_residual_mps2 = result.solve.cross_validation_residual_mps2[k];
    }
    c.positions.push_back(s);
  }
  c.warnings = result.warnings;

  // The gyroscope from the turns between the same positions, with the
  // gravity directions of the accelerometer just calibrated.
  if (options.calibrate_gyroscope && !recording.gyro_radps.empty() &&
      result.solve.converged()) {
    // The accelerometer's calibration stands without it: a gyroscope that
    // cannot be calibrated is a warning, not a failure of the whole.
    try {
      result.gyro = CalibrateGyroscope(recording, intervals, c, options.gyro);
      if (result.gyro->converged()) c.gyroscope = result.gyro->calibration;
    } catch (const Error& e) {
      result.warnings.push_back(std::string("gyroscope not calibrated: ") + e.what());
      c.warnings = result.warnings;
    }
  }
  return result;
}

}  // namespace mpcal
