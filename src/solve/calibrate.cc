// A whole calibration from a recording: detection, units, solve, packaging.
#include "mpcal/calibrate.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <utility>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Geometry>

#include "mpcal/coverage.h"
#include "mpcal/error.h"
#include "mpcal/gravity.h"
#include "mpcal/plausible.h"
#include "mpcal/sphere_fit.h"

namespace mpcal {
namespace {

// The mean gyroscope reading over a position (raw units): its bias at rest.
Eigen::Vector3d GyroMean(const RecordingView& r, const StaticInterval& iv) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (std::size_t i = iv.begin; i < iv.end; ++i) sum += r.gyro_radps[i];
  return sum / static_cast<double>(iv.end - iv.begin);
}

// One turn's samples and the directions of gravity at its two ends.
struct TurnSpan {
  std::size_t begin = 0;
  std::size_t end = 0;
  Eigen::Vector3d bias_raw = Eigen::Vector3d::Zero();
  Eigen::Vector3d u_from = Eigen::Vector3d::UnitZ();
  Eigen::Vector3d u_to = Eigen::Vector3d::UnitZ();
};

Eigen::Matrix3d TurnRotation(const RecordingView& r, const TurnSpan& span, double scale) {
  GyroCalibration nominal;
  nominal.input_units = r.gyro_units;
  nominal.radps_per_unit = scale;
  nominal.bias_radps = span.bias_raw * scale;
  return IntegrateRotation(r, span.begin, span.end, nominal);
}

double AngleBetweenDeg(const Eigen::Vector3d& u, const Eigen::Vector3d& v) {
  return std::atan2(u.cross(v).norm(), u.dot(v)) * 180.0 / std::numbers::pi;
}

// Sum of the squared tilts (deg²) between each gravity direction carried
// over its turn at `scale` and the one measured after it.
double TiltCost(const RecordingView& r,
                const std::vector<TurnSpan>& spans,
                double scale) {
  double cost = 0.0;
  for (const TurnSpan& span : spans) {
    const Eigen::Matrix3d rot = TurnRotation(r, span, scale);
    const double tilt = AngleBetweenDeg(rot.transpose() * span.u_from, span.u_to);
    cost += tilt * tilt;
  }
  return cost;
}

// The one common scale of raw counts (rad/s per count) that best carries the
// directions over the turns: a log grid from 1e-7 to 1e-1 (the step, 19 %,
// keeps a 90 deg turn within 17 deg of its basin), then golden section.
double CountsScale(const RecordingView& r, const std::vector<TurnSpan>& spans) {
  constexpr int kGrid = 80;
  constexpr double kLogLo = -7.0;
  constexpr double kLogHi = -1.0;
  const double step = (kLogHi - kLogLo) / kGrid;
  double best_log = kLogLo;
  double best = std::numeric_limits<double>::infinity();
  for (int k = 0; k <= kGrid; ++k) {
    const double l = kLogLo + k * step;
    const double c = TiltCost(r, spans, std::pow(10.0, l));
    if (c < best) {
      best = c;
      best_log = l;
    }
  }
  double lo = best_log - step;
  double hi = best_log + step;
  const double ratio = (std::sqrt(5.0) - 1.0) / 2.0;
  for (int it = 0; it < 40; ++it) {
    const double a = hi - ratio * (hi - lo);
    const double b = lo + ratio * (hi - lo);
    if (TiltCost(r, spans, std::pow(10.0, a)) < TiltCost(r, spans, std::pow(10.0, b))) {
      hi = b;
    } else {
      lo = a;
    }
  }
  return std::pow(10.0, 0.5 * (lo + hi));
}

}  // namespace

std::vector<Turn> MeasureTurns(const RecordingView& recording,
                               std::span<const StaticInterval> intervals,
                               double* scale_radps_per_unit) {
  std::vector<Turn> turns;
  if (recording.gyro_radps.empty() || intervals.size() < 2) return turns;
  for (const StaticInterval& iv : intervals) {
    if (!(iv.begin < iv.end) || iv.end > recording.gyro_radps.size()) {
      throw Error(ErrorKind::kInput,
                  fmt::format("{}: a position (samples {}-{}) lies outside the {} "
                              "gyroscope samples",
                              recording.source,
                              iv.begin,
                              iv.end,
                              recording.gyro_radps.size()));
    }
  }
  std::vector<Eigen::Vector3d> means;
  for (const StaticInterval& iv : intervals) means.push_back(iv.mean);
  const Eigen::Vector3d centre = FitSphere(means, recording.units).centre;
  // The turns between the positions grown to the motion, as the gyroscope's
  // calibration integrates them.
  const std::vector<StaticInterval> edges = ExtendToMotion(recording, intervals);
  std::vector<TurnSpan> spans;
  for (std::size_t k = 0; k + 1 < intervals.size(); ++k) {
    TurnSpan span;
    span.begin = edges[k].end - 1;
    span.end = edges[k + 1].begin;
    span.bias_raw =
        0.5 * (GyroMean(recording, intervals[k]) + GyroMean(recording, intervals[k + 1]));
    span.u_from = (intervals[k].mean - centre).normalized();
    span.u_to = (intervals[k + 1].mean - centre).normalized();
    spans.push_back(span);
  }
  const auto fixed = FixedRadpsPerUnit(recording.gyro_units);
  const double scale = fixed ? *fixed : CountsScale(recording, spans);
  if (scale_radps_per_unit != nullptr) *scale_radps_per_unit = scale;
  for (std::size_t k = 0; k < spans.size(); ++k) {
    const Eigen::AngleAxisd rotation(TurnRotation(recording, spans[k], scale));
    Turn turn;
    turn.from = k;
    turn.start_s = recording.time_s[spans[k].begin];
    turn.end_s = recording.time_s[spans[k].end];
    turn.angle_deg = rotation.angle() * 180.0 / std::numbers::pi;
    turn.axis = rotation.axis();
    turn.tilt_deg = AngleBetweenDeg(spans[k].u_from, spans[k].u_to);
    turns.push_back(turn);
  }
  return turns;
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

namespace {

// Throws a SessionError unless the detection found enough positions for
// the model.
void RequireEnoughPositions(const RecordingView& recording,
                            const DetectResult& detection,
                            const CalibrateOptions& options) {
  const auto& intervals = detection.intervals;
  if (intervals.empty()) {
    throw SessionError(SessionProblem::kNoPositions,
                       std::string(recording.source),
                       detection,
                       {},
                       Describe(detection.finding),
                       detection.finding.advice);
  }
  if (static_cast<int>(intervals.size()) < ParameterCount(options.solve.model)) {
    CoverageOptions coverage;
    coverage.model = options.solve.model;
    coverage.units = recording.units;
    CoverageResult assessed = AssessCoverage(detection, coverage);
    const std::string what = fmt::format("{}: {}", recording.source, Summary(assessed));
    throw SessionError(SessionProblem::kTooFewPositions,
                       std::string(recording.source),
                       detection,
                       std::move(assessed),
                       what,
                       Advice{{}, Stage::kDetect, std::string(recording.source)});
  }
}

// Raw counts: the nominal scale is the radius of the sphere the position
// means lie on, so that the model's scale-factor errors stay small numbers
// and the six-position initialisation works as for any other unit. Returns
// the nominal offset (m/s²) and sets result->mps2_per_unit.
Eigen::Vector3d NominalScale(const RecordingView& recording,
                             const CalibrateOptions& options,
                             CalibrateResult* result) {
  const auto& intervals = result->detection.intervals;
  Eigen::Vector3d nominal_offset_mps2 = Eigen::Vector3d::Zero();
  if (const auto fixed = FixedMps2PerUnit(recording.units)) {
    result->mps2_per_unit = *fixed;
  } else {
    std::vector<Eigen::Vector3d> means;
    means.reserve(intervals.size());
    for (const auto& in : intervals) means.push_back(in.mean);
    const SphereFit sphere = FitSphere(means, AccelUnits::kCounts);
    if (!sphere.fitted || !(sphere.radius > 0.0)) {
      throw SessionError(
          SessionProblem::kCountsNotSpread,
          std::string(recording.source),
          result->detection,
          {},
          fmt::format("{}: the {} static positions do not spread over the sphere, so the "
                      "offset and scale of the raw counts cannot be found from them; "
                      "record positions with each axis up and down",
                      recording.source,
                      intervals.size()),
          Advice{{{Option::kLogUnits, "counts"}},
                 Stage::kDetect,
                 std::string(recording.source)});
    }
    result->mps2_per_unit = options.counts_per_g > 0.0
                                ? kStandardGravityMps2 / options.counts_per_g
                                : options.solve.gravity_mps2 / sphere.radius;
    nominal_offset_mps2 = sphere.centre * result->mps2_per_unit;
  }

  return nominal_offset_mps2;
}

// The calibration file's content from the solve.
void Package(const RecordingView& recording,
             const CalibrateOptions& options,
             CalibrateResult* result_ptr) {
  CalibrateResult& result = *result_ptr;
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
}

// The gyroscope from the turns between the same positions, with the gravity
// directions of the accelerometer just calibrated.
void CalibrateGyroscopeToo(const RecordingView& recording,
                           const CalibrateOptions& options,
                           CalibrateResult* result_ptr) {
  CalibrateResult& result = *result_ptr;
  const auto& intervals = result.detection.intervals;
  Calibration& c = result.calibration;
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
}

}  // namespace

CalibrateResult CalibrateRecording(const RecordingView& recording,
                                   const CalibrateOptions& options) {
  if (const std::string problem = options.Validate(); !problem.empty()) {
    throw Error(ErrorKind::kOption, "calibration options: " + problem);
  }
  CalibrateResult result;
  CheckUnits(recording, options.solve.gravity_mps2);
  result.detection = DetectStatic(recording, options.detect);
  RequireEnoughPositions(recording, result.detection, options);
  const Eigen::Vector3d nominal_offset_mps2 = NominalScale(recording, options, &result);
  const auto& intervals = result.detection.intervals;
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
  // Positions dropped for clipping, then the solver's.
  for (const auto& note : result.detection.notes)
    result.warnings.push_back(Describe(note));
  result.warnings.insert(
      result.warnings.end(), result.solve.warnings.begin(), result.solve.warnings.end());

  Package(recording, options, &result);
  CalibrateGyroscopeToo(recording, options, &result);
  return result;
}

}  // namespace mpcal
