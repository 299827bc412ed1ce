/// \file advice.h
/// \brief What would change an outcome, as facts: the Options field to set
/// (with the value the data suggest, when they suggest one) or the stage to
/// run to see more.
///
/// The library never spells these as command-line flags or subcommands: a
/// caller names them in its own terms. The `mpcal` command turns them into
/// flags and subcommands in one place (apps/mpcal/explain.cc, from the table
/// that declares the flags); a C++ program or the Python module can spell
/// them as it likes.
#pragma once

#include <string>
#include <vector>

namespace mpcal {

/// One field of an Options struct that a finding or an error can point at.
/// The comment beside each names the field.
enum class Option {
  kNone,
  kLogColumns,          ///< LogOptions::columns
  kLogUnits,            ///< LogOptions::units
  kLogTimeUnit,         ///< LogOptions::time_unit
  kLogRate,             ///< LogOptions::rate_hz
  kLogGyroUnits,        ///< LogOptions::gyro_in_dps / gyro_in_counts
  kLogTopic,            ///< LogOptions::topic (a ROS bag or MCAP file)
  kLogRecordingTime,    ///< LogOptions::recording_time (a ROS bag or MCAP file)
  kGyroLog,             ///< the gyroscope's own log (gyro_log.h: ReadGyroLog's path)
  kGyroLogColumns,      ///< LogOptions::columns of the gyroscope's own log
  kAccelTopic,          ///< LogOptions::topic when the gyroscope has a topic of its own
  kGyroTopic,           ///< LogOptions::topic of the gyroscope's own stream
  kGravity,             ///< the gravity magnitude (CalibrateOptions::solve.gravity_mps2)
  kLatitude,            ///< the site's latitude, for normal gravity
  kHeight,              ///< the site's height, for normal gravity
  kModel,               ///< SolveOptions::model
  kRobust,              ///< SolveOptions::robust
  kDetectWindow,        ///< DetectOptions::window_s
  kDetectMinStatic,     ///< DetectOptions::min_static_s
  kDetectSettle,        ///< DetectOptions::settle_s
  kDetectThreshold,     ///< DetectOptions::threshold
  kDetectMaxStill,      ///< DetectOptions::max_still_s
  kDetectMergeGap,      ///< DetectOptions::merge_gap_s
  kDetectMergeAngle,    ///< DetectOptions::merge_angle
  kSensorRange,         ///< the sensor's full-scale range (clipping)
  kTimeOffset,          ///< VerifyOptions: the clock offset to the reference
  kTimeAlign,           ///< VerifyOptions: how to align the clocks
  kMount,               ///< IntegrateOptions::mount
  kGnssFormat,          ///< GnssOptions: the reference's format
  kVerifyTrajectories,  ///< ReportInputs: the trajectories of a verification
};

/// A stage of the library a caller can run to see more (the command line
/// runs it as a subcommand).
enum class Stage {
  kNone,
  kDetect,
  kCalibrate,
  kApply,
  kVerify,
  kRepeat,
  kNoise,
  kSimulate,
  kReport,
};

/// One option and the value to give it. An empty value means the value is
/// the user's to choose (the caller shows its placeholder, e.g. "HZ").
struct Setting {
  Option option = Option::kNone;
  std::string value;
};

/// What would change an outcome: settings (alternatives, any one of which
/// would do), and/or a stage to run on `stage_input` to see more. Empty
/// when there is nothing to suggest.
struct Advice {
  std::vector<Setting> settings;
  Stage stage = Stage::kNone;
  std::string stage_input;

  bool empty() const { return settings.empty() && stage == Stage::kNone; }
};

}  // namespace mpcal
