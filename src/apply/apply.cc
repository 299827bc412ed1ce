#include "mpcal/apply.h"

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <cmath>
#include <ostream>
#include <string_view>

#include <fmt/format.h>

#include "mpcal/atomic_file.h"
#include "mpcal/error.h"

namespace mpcal {
namespace {

// Rows per block of the magnitude-at-rest check, and the blocks kept: a
// bounded summary of the log's start, so memory stays constant.
constexpr std::size_t kRestBlockRows = 32;
constexpr std::size_t kRestMaxBlocks = 8192;
// Output is gathered and handed to the stream in pieces of this size.
constexpr std::size_t kOutputChunk = std::size_t{1} << 20;

struct RestBlock {
  double magnitude;      // mean corrected |a|, m/s²
  double raw_magnitude;  // mean |reading| × nominal scale, m/s²
  double motion;         // trace of the covariance of a, (m/s²)²
};

// Running sums of one block. Magnitudes are averaged sample by sample, so
// that a block spanning two orientations still measures |a|; such a block
// moves more than a still one and is not among the quietest anyway.
struct BlockSums {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double sum_norm = 0.0;
  double raw_sum_norm = 0.0;
  double sum_sq = 0.0;
  std::size_t n = 0;

  void Add(const Eigen::Vector3d& a_mps2, const Eigen::Vector3d& raw) {
    sum += a_mps2;
    const double sq = a_mps2.squaredNorm();
    sum_sq += sq;
    sum_norm += std::sqrt(sq);
    raw_sum_norm += raw.norm();
    ++n;
  }
  RestBlock Close(double raw_mps2_per_unit) const {
    const double count = static_cast<double>(n);
    const Eigen::Vector3d mean = sum / count;
    return {sum_norm / count,
            raw_mps2_per_unit * raw_sum_norm / count,
            std::max(0.0, sum_sq / count - mean.squaredNorm())};
  }
};

struct Rest {
  double magnitude_mps2;
  double raw_magnitude_mps2;
};

std::optional<Rest> RestMagnitude(std::vector<RestBlock> blocks) {
  if (blocks.empty()) return std::nullopt;
  // The quietest quarter: at rest, or as close to it as the log comes.
  std::sort(blocks.begin(), blocks.end(), [](const RestBlock& a, const RestBlock& b) {
    return a.motion < b.motion;
  });
  const std::size_t quiet = std::max<std::size_t>(1, blocks.size() / 4);
  std::vector<double> magnitudes;
  std::vector<double> raw;
  for (std::size_t i = 0; i < quiet; ++i) {
    magnitudes.push_back(blocks[i].magnitude);
    raw.push_back(blocks[i].raw_magnitude);
  }
  std::nth_element(magnitudes.begin(), magnitudes.begin() + quiet / 2, magnitudes.end());
  std::nth_element(raw.begin(), raw.begin() + quiet / 2, raw.end());
  return Rest{magnitudes[quiet / 2], raw[quiet / 2]};
}

// The unit in brackets of an accelerometer column's name, as written for
// `units`: "m/s^2" (phyphox's spelling), "g"; empty for counts.
bool IsUnitLabelOf(std::string_view label, AccelUnits units) {
  std::string l;
  for (char c : label) {
    if (c != ' ')
      l.push_back(static_cast<char>(std::tolower(static_cast<unsigned char>(c))));
  }
  if (units == AccelUnits::kG) return l == "g";
  if (units == AccelUnits::kMps2) {
    return l == "m/s^2" || l == "m/s2" || l == "m/s\xc2\xb2" || l == "ms^-2" ||
           l == "ms-2" || l == "mps2";
  }
  return false;
}

// The header with the unit in brackets after each accelerometer column's
// name rewritten for the corrected readings: with g out of a log in m/s²,
// "Acceleration x (m/s^2)" becomes "Acceleration x (g)". Other columns, and
// names without a unit, stay as they are.
std::string RelabelHeader(std::string_view header,
                          const LogLayout& layout,
                          AccelUnits from,
                          AccelUnits to) {
  if (from == to || layout.delimiter == ' ') return std::string(header);
  const std::string_view label = to == AccelUnits::kG ? "g" : "m/s^2";
  std::string out;
  int column = 0;
  std::size_t start = 0;
  while (start <= header.size()) {
    std::size_t stop = header.find(layout.delimiter, start);
    if (stop == std::string_view::npos) stop = header.size();
    std::string field(header.substr(start, stop - start));
    const bool accel =
        std::find(layout.accel_columns.begin(), layout.accel_columns.end(), column) !=
        layout.accel_columns.end();
    const std::size_t open = field.find_first_of("([");
    if (accel && open != std::string::npos) {
      const char close = field[open] == '(' ? ')' : ']';
      const std::size_t end = field.find(close, open + 1);
      if (end != std::string::npos &&
          IsUnitLabelOf(std::string_view(field).substr(open + 1, end - open - 1), from)) {
        field.replace(open + 1, end - open - 1, label);
      }
    }
    out += field;
    if (stop == header.size()) break;
    out += layout.delimiter;
    start = stop + 1;
    ++column;
  }
  return out;
}

}  // namespace

void CheckCalibrationApplies(const Calibration& calibration, AccelUnits log_units) {
  const bool cal_counts = calibration.input_units == AccelUnits::kCounts;
  const bool log_counts = log_units == AccelUnits::kCounts;
  if (cal_counts && !log_counts) {
    throw Error(fmt::format(
        "the calibration is for raw counts (input.units 'counts', {:.6g} m/s² per count) "
        "but "
        "the log is read as '{}': apply it to logs of the same sensor in counts (--units "
        "counts), or calibrate from a log in '{}'",
        calibration.mps2_per_unit,
        ToString(log_units),
        ToString(log_units)));
  }
  if (log_counts && !cal_counts) {
    throw Error(
        fmt::format("the log is read as raw counts (--units counts) but the calibration "
                    "is for readings "
                    "in '{}', which have no scale for counts: give the log's real units "
                    "with --units, or "
                    "calibrate from a log in counts",
                    ToString(calibration.input_units)));
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
    throw Error("the calibration's gyroscope model is not finite");
  }
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
  if (!problem.empty()) throw Error("apply options: " + problem);
  RefuseOverwritingInput(input, output);

  ApplyResult result;
  const AccelUnits log_units = options.log.units;
  result.out_units = options.out_units.value_or(
      log_units == AccelUnits::kCounts ? AccelUnits::kMps2 : log_units);
  // Validate before touching the input: a wrong calibration is reported
  // without reading a byte of a long log.
  const Corrector correct(calibration, log_units, result.out_units);
  const double mps2_per_out = 1.0 / correct.out_per_mps2();
  const double raw_mps2_per_unit = log_units == AccelUnits::kCounts
                                       ? calibration.mps2_per_unit
                                       : *FixedMps2PerUnit(log_units);

  LogScanner scanner(
      input, options.log, /*parse_gyro=*/calibration.gyroscope.has_value());
  const char decimal_point = scanner.layout().decimal_point;
  // The gyroscope columns too, when both the calibration and the log have them.
  std::optional<GyroCorrector> correct_gyro;
  if (calibration.gyroscope && scanner.layout().has_gyro()) {
    const GyroUnits log_gyro = options.log.gyro_in_counts ? GyroUnits::kCounts
                               : options.log.gyro_in_dps  ? GyroUnits::kDps
                                                          : GyroUnits::kRadps;
    result.out_gyro_units = options.out_gyro_units.value_or(
        log_gyro == GyroUnits::kCounts ? GyroUnits::kRadps : log_gyro);
    correct_gyro.emplace(*calibration.gyroscope, log_gyro, result.out_gyro_units);
    result.gyro_corrected = true;
  }

  std::vector<RestBlock> blocks;
  BlockSums block;
  WriteStreamAtomically(output, [&](std::ostream& out) {
    std::string buffer;
    buffer.reserve(kOutputChunk + 4096);
    LogLine line;
    while (scanner.Next(&line)) {
      if (!line.is_data) {
        ++result.other_lines;
        if (line.line_number == scanner.layout().header_line) {
          buffer.append(
              RelabelHeader(line.text, scanner.layout(), log_units, result.out_units));
        } else {
          buffer.append(line.text);
        }
        buffer.append(line.eol);
      } else {
        ++result.data_rows;
        const Eigen::Vector3d a = correct(line.accel);
        if (blocks.size() < kRestMaxBlocks) {
          block.Add(a * mps2_per_out, line.accel);
          if (block.n == kRestBlockRows) {
            blocks.push_back(block.Close(raw_mps2_per_unit));
            block = BlockSums();
          }
        }
        // Replace the numbers (accelerometer, then gyroscope: indices 3-5)
        // in the order they appear on the line.
        Eigen::Matrix<double, 6, 1> values;
        values << a, correct_gyro ? (*correct_gyro)(line.gyro, a * mps2_per_out)
                                  : Eigen::Vector3d::Zero();
        auto span = [&](int i) {
          return i < 3 ? line.accel_span[i] : line.gyro_span[i - 3];
        };
        std::array<int, 6> order = {0, 1, 2, 3, 4, 5};
        const int count = correct_gyro ? 6 : 3;
        std::sort(order.begin(), order.begin() + count, [&](int i, int j) {
          return span(i).first < span(j).first;
        });
        std::size_t copied = 0;
        for (int k = 0; k < count; ++k) {
          const int axis = order[static_cast<std::size_t>(k)];
          const auto [begin, end] = span(axis);
          buffer.append(line.text.substr(copied, begin - copied));
          char number[32];
          const auto r = std::to_chars(number, number + sizeof(number), values[axis]);
          if (decimal_point != '.') std::replace(number, r.ptr, '.', decimal_point);
          buffer.append(number, r.ptr);
          copied = end;
        }
        buffer.append(line.text.substr(copied));
        buffer.append(line.eol);
      }
      if (buffer.size() >= kOutputChunk) {
        out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
        buffer.clear();
      }
    }
    if (result.data_rows == 0) {
      throw Error(fmt::format("'{}' has no data rows to correct", scanner.source()));
    }
    out.write(buffer.data(), static_cast<std::streamsize>(buffer.size()));
  });

  result.warnings = scanner.warnings();
  if (block.n > 0 && blocks.size() < kRestMaxBlocks) {
    blocks.push_back(block.Close(raw_mps2_per_unit));
  }
  const std::optional<Rest> rest = RestMagnitude(std::move(blocks));
  if (rest) {
    result.rest_magnitude_mps2 = rest->magnitude_mps2;
    const double g = calibration.gravity_mps2;
    const double m = rest->magnitude_mps2;
    if (std::abs(m - g) > options.rest_tolerance * g) {
      // The raw readings tell a units mix-up (a factor 9.8) from a sensor
      // mix-up (errors of a few percent).
      const double raw_ratio = rest->raw_magnitude_mps2 / g;
      std::string hint =
          "is it the calibrated sensor, and are the log's units right (--units)?";
      if (log_units != AccelUnits::kCounts) {
        if (std::abs(raw_ratio * kStandardGravityMps2 - 1.0) < 0.2) {
          hint = "the log looks like it is in g: use --units g";
        } else if (std::abs(raw_ratio / kStandardGravityMps2 - 1.0) < 0.2) {
          hint = "the log looks like it is in m/s²: use --units mps2";
        }
      }
      result.warnings.push_back(
          fmt::format("{}: the corrected magnitude at rest is {:.4g} m/s², {:.1f}% from "
                      "the calibration's "
                      "gravity {:.6g} m/s²; {}",
                      scanner.source(),
                      m,
                      100.0 * (m - g) / g,
                      g,
                      hint));
    }
  }
  return result;
}

}  // namespace mpcal
