// The gyroscope as people read it, beside the accelerometer's table: M as
// scale-factor errors (ppm) and misalignments (mrad) ±1σ, the bias (deg/s)
// and its change over the session, the turn residuals before and after;
// and the session's gyroscope findings in words. Shared by `calibrate` and
// `demo`.
#pragma once

#include <span>
#include <string>
#include <vector>

#include "mpcal/calibrate.h"
#include "mpcal/calibration.h"
#include "mpcal/gyro.h"
#include "mpcal/gyro_calibration.h"

namespace mpcal::cli {

/// An optional column beside the estimate (the truth, say), as a calibration;
/// with `details`, the bias's change over the session and the nominal scale
/// of raw counts under it.
std::string FormatGyroTable(const GyroCalibration& gyro,
                            const GyroCalibration* extra = nullptr,
                            const std::string& extra_title = "",
                            bool details = true);

/// Turns, convergence and the RMS tilt before/after, a few lines.
std::string FormatGyroSummary(const GyroResult& result);

/// Each finding as a sentence naming the entries of M and the turns to add;
/// first, when the fit did not converge, a line saying so.
std::vector<std::string> GyroFindingMessages(const GyroResult& result);

/// `mpcal repeat` over IMU files or logs with a gyroscope: per entry of M
/// (ppm, mrad) and bias (deg/s), each trial's value, the mean, the sample
/// std and whether the trials differ beyond their 1σ (chi-square of the
/// trials against their weighted mean, 1 % significance). Empty when fewer
/// than two trials have a gyroscope.
std::string FormatGyroRepeatTable(std::span<const Calibration> trials,
                                  std::span<const std::string> names);

}  // namespace mpcal::cli
