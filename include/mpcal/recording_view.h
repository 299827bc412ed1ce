/// \file recording_view.h
/// \brief A recording's rows seen where they are, without a copy.
#pragma once

#include <cstddef>
#include <span>
#include <string_view>

#include <Eigen/Core>

#include "mpcal/recording.h"
#include "mpcal/units.h"

namespace mpcal {

/// A recording's rows where they already are, for what only reads them
/// (detection, the calibration of both sensors): a Recording's own vectors
/// (a Recording converts to its view), or memory of the caller's, such as
/// the numpy arrays the Python module is given, which then need not be
/// copied into a Recording first.
///
/// The view owns nothing. The rows and the text `source` views must outlive
/// every call given the view, and stay unchanged while it reads them: a
/// view kept after its Recording is destroyed or resized dangles. Fields as
/// Recording's; `gyro_radps` is empty without a gyroscope.
struct RecordingView {
  std::span<const double> time_s;
  std::span<const Eigen::Vector3d> accel;
  std::span<const Eigen::Vector3d> gyro_radps;
  /// A gyroscope recorded apart: its own samples and their times, as
  /// Recording's (empty when the gyroscope came on the rows).
  std::span<const double> gyro_samples_time_s;
  std::span<const Eigen::Vector3d> gyro_samples;
  GyroUnits gyro_units = GyroUnits::kRadps;
  GyroUnits gyro_log_units = GyroUnits::kRadps;
  AccelUnits units = AccelUnits::kMps2;
  std::string_view source;

  RecordingView() = default;
  /// The rows of `recording`, as they are (no copy).
  // NOLINTNEXTLINE(google-explicit-constructor): every reader takes a Recording this way
  RecordingView(const Recording& recording)
      : time_s(recording.time_s),
        accel(recording.accel),
        gyro_radps(recording.gyro_radps),
        gyro_samples_time_s(recording.gyro_samples_time_s),
        gyro_samples(recording.gyro_samples),
        gyro_units(recording.gyro_units),
        gyro_log_units(recording.gyro_log_units),
        units(recording.units),
        source(recording.source) {}

  std::size_t size() const { return time_s.size(); }
  bool empty() const { return time_s.empty(); }
};

/// `rows` rows of (x, y, z) held as 3·rows doubles in row order (an N×3
/// C-order array), seen as the vectors a RecordingView takes: no copy.
/// `xyz` must be aligned as a double is (a Vector3d is three doubles, no
/// padding, no stricter alignment).
inline std::span<const Eigen::Vector3d> XyzRows(const double* xyz, std::size_t rows) {
  static_assert(sizeof(Eigen::Vector3d) == 3 * sizeof(double) &&
                alignof(Eigen::Vector3d) == alignof(double));
  // NOLINTNEXTLINE(cppcoreguidelines-pro-type-reinterpret-cast): same layout, above
  return {reinterpret_cast<const Eigen::Vector3d*>(xyz), rows};
}

}  // namespace mpcal
