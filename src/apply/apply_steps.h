// The steps of ApplyCalibration (apply.cc), private to the apply room: the
// summary of the log's start that the magnitude-at-rest check reads, the
// check itself, the header's unit labels and the rewriting of one data row.
// Tests reach them through this header.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "mpcal/apply.h"
#include "mpcal/log_reader.h"

namespace mpcal::internal {

/// The magnitude at rest: the median over the quietest quarter of the blocks
/// of the corrected |a| and of the raw |reading| × nominal scale (m/s²).
struct Rest {
  double magnitude_mps2 = 0.0;
  double raw_magnitude_mps2 = 0.0;
};

/// A bounded summary of the log's start (blocks of 32 rows, at most 8192
/// blocks), so that memory stays constant however long the log.
class RestSummary {
 public:
  explicit RestSummary(double raw_mps2_per_unit)
      : raw_mps2_per_unit_(raw_mps2_per_unit) {}
  /// One row: the corrected specific force (m/s²) and the raw reading.
  void Add(const Eigen::Vector3d& a_mps2, const Eigen::Vector3d& raw);
  /// The magnitude at rest; empty without rows.
  std::optional<Rest> Finish();

 private:
  struct Block {
    double magnitude;      // mean corrected |a|, m/s²
    double raw_magnitude;  // mean |reading| × nominal scale, m/s²
    double motion;         // trace of the covariance of a, (m/s²)²
  };
  void Close();

  double raw_mps2_per_unit_;
  std::vector<Block> blocks_;
  Eigen::Vector3d sum_ = Eigen::Vector3d::Zero();
  double sum_norm_ = 0.0;
  double raw_sum_norm_ = 0.0;
  double sum_sq_ = 0.0;
  std::size_t n_ = 0;
};

/// The magnitude-at-rest check: empty when `rest` is within `tolerance` (a
/// fraction) of `gravity_mps2`; otherwise the finding, telling a units
/// mix-up (a factor 9.8 in the raw readings) from another sensor.
std::optional<RestMismatch> CheckRestMagnitude(const Rest& rest,
                                               double gravity_mps2,
                                               double tolerance,
                                               AccelUnits log_units,
                                               std::string_view source);

/// The header with the unit in brackets after each accelerometer column's
/// name rewritten for the corrected readings ("(m/s^2)" becomes "(g)").
std::string RelabelHeader(std::string_view header,
                          const LogLayout& layout,
                          AccelUnits from,
                          AccelUnits to);

/// `line` with its first `count` numbers (accelerometer x, y, z, then
/// gyroscope x, y, z) replaced by `values`, in the order they appear on the
/// line, written in the shortest form with the log's decimal point; appended
/// to `out` with the line's end.
void AppendCorrectedRow(const LogLine& line,
                        const Eigen::Matrix<double, 6, 1>& values,
                        int count,
                        char decimal_point,
                        std::string& out);

}  // namespace mpcal::internal
