#include "mpcal/gyro_log.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "mpcal/error.h"

namespace mpcal {

Recording ReadGyroLog(const std::string& path, LogOptions options) {
  options.gyroscope_only = true;
  // The reader bounds each reading by its units (plausible.h): a gyroscope's
  // counts may span the ADC's range, a rate in rad/s or deg/s stays far
  // below the bound of m/s².
  options.units = options.gyro_in_counts ? AccelUnits::kCounts : AccelUnits::kMps2;
  return ReadLog(path, options);
}

void MergeGyroLog(Recording& recording, const Recording& gyro_log, GyroUnits units) {
  if (!recording.gyro_radps.empty()) {
    throw Error(
        fmt::format("{} already has gyroscope columns; give the gyroscope either in "
                    "it or in {}, not both",
                    recording.source,
                    gyro_log.source));
  }
  if (gyro_log.size() != recording.size()) {
    throw Error(
        fmt::format("{} has {} rows but {} has {}: the gyroscope log must hold the "
                    "same samples, row by row",
                    gyro_log.source,
                    gyro_log.size(),
                    recording.source,
                    recording.size()));
  }
  const std::size_t n = recording.size();
  double period = n > 1 ? (recording.time_s.back() - recording.time_s.front()) /
                              static_cast<double>(n - 1)
                        : 1.0;
  // A hundredth of a sample: the two files were written by one logger.
  const double tolerance = 0.01 * period;
  for (std::size_t i = 0; i < n; ++i) {
    if (std::abs(gyro_log.time_s[i] - recording.time_s[i]) > tolerance) {
      throw Error(
          fmt::format("{}: data row {} is at {:.9g} s but row {} of {} is at {:.9g} s: "
                      "the two logs are not the same samples",
                      gyro_log.source,
                      i + 1,
                      gyro_log.time_s[i],
                      i + 1,
                      recording.source,
                      recording.time_s[i]));
    }
  }
  const double scale = units == GyroUnits::kCounts ? 1.0 : *FixedRadpsPerUnit(units);
  recording.gyro_radps.resize(n);
  std::transform(gyro_log.accel.begin(),
                 gyro_log.accel.end(),
                 recording.gyro_radps.begin(),
                 [scale](const Eigen::Vector3d& v) { return (v * scale).eval(); });
  recording.gyro_units =
      units == GyroUnits::kCounts ? GyroUnits::kCounts : GyroUnits::kRadps;
  recording.gyro_log_units = units;
}

}  // namespace mpcal
