#include "mpcal/apply.h"

#include <cmath>
#include <ostream>
#include <utility>

#include <fmt/format.h>

#include "apply/apply_steps.h"
#include "mpcal/atomic_file.h"
#include "mpcal/error.h"

namespace mpcal {
namespace {

// Advice to read the log in `units` (empty: the user's to choose).
Advice ReadLogIn(std::string units) {
  Advice advice;
  advice.settings = {{Option::kLogUnits, std::move(units)}};
  return advice;
}

// Output is gathered and handed to the stream in pieces of this size.
constexpr std::size_t kOutputChunk = std::size_t{1} << 20;

// The gyroscope's corrector, when both the calibration and the log have a
// gyroscope; records the output units in `result`.
std::optional<GyroCorrector> MakeGyroCorrector(const Calibration& calibration,
                                               const LogLayout& layout,
                                               const ApplyOptions& options,
                                               ApplyResult& result) {
  if (!calibration.gyroscope || !layout.has_gyro()) return std::nullopt;
  const GyroUnits log_gyro = options.log.gyro_units();
  result.out_gyro_units = options.out_gyro_units.value_or(
      log_gyro == GyroUnits::kCounts ? GyroUnits::kRadps : log_gyro);
  result.gyro_corrected = true;
  result.log_gyro_units = log_gyro;
  return GyroCorrector(*calibration.gyroscope, log_gyro, result.out_gyro_units);
}

// What one pass over the log needs: the correctors, the summary of the rest,
// and the counts it keeps.
struct RowRewriter {
  const Corrector& correct;
  const std::optional<GyroCorrector>& correct_gyro;
  double mps2_per_out;
  AccelUnits log_units;
  internal::RestSummary& rest;
  ApplyResult& result;

  // Appends `line`, corrected when it is a data row, to `buffer`.
  void Append(const LogLine& line, const LogLayout& layout, std::string& buffer) const {
    if (!line.is_data) {
      ++result.other_lines;
      if (line.line_number == layout.header_line) {
        buffer.append(
            internal::RelabelHeader(line.text, layout, log_units, result.out_units));
      } else {
        buffer.append(line.text);
      }
      buffer.append(line.eol);
      return;
    }
    ++result.data_rows;
    const Eigen::Vector3d a = correct(line.accel);
    rest.Add(a * mps2_per_out, line.accel);
    // Accelerometer, then gyroscope: indices 3-5.
    Eigen::Matrix<double, 6, 1> values;
    values << a, correct_gyro ? (*correct_gyro)(line.gyro, a * mps2_per_out)
                              : Eigen::Vector3d::Zero();
    internal::AppendCorrectedRow(
        line, values, correct_gyro ? 6 : 3, layout.decimal_point, buffer);
  }
};

}  // namespace

void CheckCalibrationApplies(const Calibration& calibration, AccelUnits log_units) {
  const bool cal_counts = calibration.input_units == AccelUnits::kCounts;
  const bool log_counts = log_units == AccelUnits::kCounts;
  if (cal_counts && !log_counts) {
    throw Error(
        ErrorKind::kUnits,
        fmt::format(
            "the calibration is for raw counts (input.units 'counts', {:.6g} m/s² "
            "per count) but the log is read as '{}': apply it to logs of the same "
            "sensor in counts, or calibrate from a log in '{}'",
            calibration.mps2_per_unit,
            ToString(log_units),
            ToString(log_units)),
        ReadLogIn("counts"));
  }
  if (log_counts && !cal_counts) {
    throw Error(
        ErrorKind::kUnits,
        fmt::format("the log is read as raw counts but the calibration is for readings "
                    "in '{}', which have no scale for counts: give the log's real units, "
                    "or calibrate from a log in counts",
                    ToString(calibration.input_units)),
        ReadLogIn(""));
  }
}

Corrector::Corrector(const Calibration& calibration,
                     AccelUnits log_units,
                     AccelUnits out_units) {
  CheckCalibrationApplies(calibration, log_units);
  const double in_mps2_per_unit = log_units == AccelUnits::kCounts
                                      ? calibration.mps2_per_unit
                                      : *FixedMps2PerUnit(log_units);
  out_per_mps2_ = out_units == AccelUnits::kCounts ? 1.0 / calibration.mps2_per_unit
                                                   : 1.0 / *FixedMps2PerUnit(out_units);
  const ErrorModel& m = calibration.model;
  // a = T·diag(1/(1+s))·(k·y − b): eqs 8-10 with the trigonometry done once.
  const Eigen::Matrix3d scaled =
      m.NonOrthogonality() *
      (Eigen::Vector3d::Ones() + m.scale_factor_error).cwiseInverse().asDiagonal();
  matrix_ = scaled * (in_mps2_per_unit * out_per_mps2_);
  offset_ = scaled * m.bias_mps2 * out_per_mps2_;
  if (!matrix_.allFinite() || !offset_.allFinite()) {
    throw Error(
        ErrorKind::kInput,
        "the calibration's model is not finite (scale-factor error of -1 or an angle "
        "of 90°?)");
  }
}

GyroCorrector::GyroCorrector(const GyroCalibration& gyro,
                             GyroUnits log_units,
                             GyroUnits out_units) {
  const bool cal_counts = gyro.input_units == GyroUnits::kCounts;
  if (cal_counts != (log_units == GyroUnits::kCounts)) {
    throw Error(
        ErrorKind::kUnits,
        fmt::format("the gyroscope calibration is for readings in '{}' but the log's "
                    "gyroscope is read as "
                    "'{}': raw counts and physical units do not convert without the "
                    "sensor's scale; read "
                    "the log in the calibration's units",
                    ToString(gyro.input_units),
                    ToString(log_units)));
  }
  // Readings in the log's unit → the calibration's unit → its nominal rad/s.
  const double in_radps =
      cal_counts ? gyro.radps_per_unit : *FixedRadpsPerUnit(log_units);
  const double out_per_radps = 1.0 / *FixedRadpsPerUnit(out_units);
  matrix_ = gyro.m * (in_radps * out_per_radps);
  offset_ = gyro.m * gyro.bias_radps * out_per_radps;
  if (gyro.g_sensitivity_radps_per_mps2) {
    g_term_ = gyro.m * *gyro.g_sensitivity_radps_per_mps2 * out_per_radps;
  }
  if (!matrix_.allFinite() || !offset_.allFinite()) {
    throw Error(ErrorKind::kInput, "the calibration's gyroscope model is not finite");
  }
}

namespace {

std::optional<GyroCorrector> MakeRowGyroCorrector(const Calibration& calibration,
                                                  GyroUnits log_gyro_units) {
  if (calibration.gyroscope) {
    return GyroCorrector(*calibration.gyroscope, log_gyro_units, GyroUnits::kRadps);
  }
  if (log_gyro_units == GyroUnits::kCounts) {
    Advice advice;
    advice.settings = {{Option::kLogGyroUnits, ""}};
    throw Error(ErrorKind::kUnits,
                "the gyroscope is read as raw counts but the calibration has no "
                "gyroscope to scale them: use an IMU calibration (mpcal.imu/1), or "
                "read the gyroscope in its physical units",
                advice);
  }
  return std::nullopt;
}

}  // namespace

RecordingCorrector::RecordingCorrector(const Calibration& calibration,
                                       AccelUnits log_units,
                                       GyroUnits log_gyro_units)
    : accel_(calibration, log_units, AccelUnits::kMps2),
      gyro_(MakeRowGyroCorrector(calibration, log_gyro_units)) {}

Recording RecordingCorrector::operator()(const Recording& rows) const {
  Recording out = rows;
  for (Eigen::Vector3d& a : out.accel) a = accel_(a);
  out.units = AccelUnits::kMps2;
  if (gyro_ && out.gyro_radps.size() == out.accel.size()) {
    for (std::size_t i = 0; i < out.size(); ++i) {
      out.gyro_radps[i] = (*gyro_)(out.gyro_radps[i], out.accel[i]);
    }
    out.gyro_units = GyroUnits::kRadps;
  }
  return out;
}

std::string ApplyOptions::Validate() const {
  const std::string log_problem = log.Validate();
  if (!log_problem.empty()) return "log." + log_problem;
  if (out_units && *out_units == AccelUnits::kCounts) {
    return "out_units must be mps2 or g (corrected readings have no counts)";
  }
  if (out_gyro_units && *out_gyro_units == GyroUnits::kCounts) {
    return "out_gyro_units must be rads or dps (corrected rates have no counts)";
  }
  if (!(rest_tolerance > 0.0) || !std::isfinite(rest_tolerance)) {
    return fmt::format("rest_tolerance must be a positive fraction, got {}",
                       rest_tolerance);
  }
  return "";
}

ApplyResult ApplyCalibration(const Calibration& calibration,
                             const std::string& input,
                             const std::string& output,
                             const ApplyOptions& options) {
  const std::string problem = options.Validate();
  if (!problem.empty()) throw Error(ErrorKind::kOption, "apply options: " + problem);
  RefuseOverwritingInput(input, output);

  ApplyResult result;
  const AccelUnits log_units = options.log.units;
  result.out_units = options.out_units.value_or(
      log_units == AccelUnits::kCounts ? AccelUnits::kMps2 : log_units);
  // Validate before touching the input: a wrong calibration is reported
  // without reading a byte of a long log.
  const Corrector correct(calibration, log_units, result.out_units);
  const double raw_mps2_per_unit = log_units == AccelUnits::kCounts
                                       ? calibration.mps2_per_unit
                                       : *FixedMps2PerUnit(log_units);

  LogScanner scanner(
      input, options.log, /*parse_gyro=*/calibration.gyroscope.has_value());
  const std::optional<GyroCorrector> correct_gyro =
      MakeGyroCorrector(calibration, scanner.layout(), options, result);
  internal::RestSummary rest(raw_mps2_per_unit);
  const RowRewriter rewriter{.correct = correct,
                             .correct_gyro = correct_gyro,
                             .mps2_per_out = 1.0 / correct.out_per_mps2(),
                             .log_units = log_units,
                             .rest = rest,
                             .result = result};
  WriteStreamAtomically(output, [&](std::ostream& out) {
    std::string buffer;
    buffer.reserve(kOutputChunk + 4096);
    LogLine line;
    while (scanner.Next(&line)) {
      rewriter.Append(line, scanner.layout(), buffer);
      if (buffer.size() >= kOutputChunk) {
        out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
        buffer.clear();
      }
    }
    if (result.data_rows == 0) {
      throw Error(ErrorKind::kInput,
                  fmt::format("'{}' has no data rows to correct", scanner.source()));
    }
    out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
  });

  result.warnings = scanner.warnings();
  if (const std::optional<internal::Rest> at_rest = rest.Finish()) {
    result.rest_magnitude_mps2 = at_rest->magnitude_mps2;
    result.rest_mismatch = internal::CheckRestMagnitude(*at_rest,
                                                        calibration.gravity_mps2,
                                                        options.rest_tolerance,
                                                        log_units,
                                                        scanner.source());
  }
  return result;
}

}  // namespace mpcal
