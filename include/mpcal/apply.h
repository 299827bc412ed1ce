/// \file apply.h
/// \brief Applying a calibration to a log: every accelerometer row corrected
/// by eqs 8-10 (docs/method.md §2), everything else copied as it is.
///
/// The log is streamed (LogScanner): memory does not grow with its length.
/// Comments, the header, blank lines, the other columns, the delimiters and
/// the line ends are copied byte for byte; only the three accelerometer
/// numbers of each data row are replaced, written with std::to_chars in the
/// shortest form that reads back to the same double.
#pragma once

#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "mpcal/advice.h"
#include "mpcal/bag.h"
#include "mpcal/calibration.h"
#include "mpcal/log_reader.h"
#include "mpcal/units.h"

namespace mpcal {

/// A calibration made ready for many rows: the model of Calibration::Correct
/// folded into one affine map, a = M·y − c, from a reading `y` in the log's
/// units to the specific force in the output units. Equal to
/// Calibration::Correct (scaled to the output units) to rounding.
class Corrector {
 public:
  /// \param log_units units of the readings that will be corrected.
  /// \param out_units units of the result; kCounts means "as the input
  ///   scale": specific force / calibration.mps2_per_unit.
  /// \throws mpcal::Error when the calibration does not apply to readings in
  ///   `log_units` (see CheckCalibrationApplies) or is not finite.
  Corrector(const Calibration& calibration, AccelUnits log_units, AccelUnits out_units);

  Eigen::Vector3d operator()(const Eigen::Vector3d& reading) const {
    return matrix_ * reading - offset_;
  }
  /// Output units per m/s² (1 for mps2, 1/9.80665 for g).
  double out_per_mps2() const { return out_per_mps2_; }

 private:
  Eigen::Matrix3d matrix_;
  Eigen::Vector3d offset_;
  double out_per_mps2_ = 1.0;
};

/// Checks that a calibration can correct readings in `log_units`: m/s² and g
/// convert exactly into each other; raw counts need a calibration made in
/// counts (its nominal scale is a property of that sensor), and a counts
/// calibration needs a log in counts.
/// \throws mpcal::Error naming both units and what to do.
void CheckCalibrationApplies(const Calibration& calibration, AccelUnits log_units);

/// The gyroscope's correction folded into one affine map, ω = A·r − c, from
/// a reading `r` in the log's gyroscope units to the angular rate in
/// `out_units` (kRadps or kDps).
class GyroCorrector {
 public:
  /// 	hrows mpcal::Error when the calibration is for raw counts and the
  ///   log is not (or the other way round).
  GyroCorrector(const GyroCalibration& gyro, GyroUnits log_units, GyroUnits out_units);
  /// `f_mps2`: the specific force at that sample (m/s²), for the bias's
  /// g-sensitivity when the calibration models it.
  Eigen::Vector3d operator()(const Eigen::Vector3d& reading,
                             const Eigen::Vector3d& f_mps2) const {
    return matrix_ * reading - offset_ - g_term_ * f_mps2;
  }

 private:
  Eigen::Matrix3d matrix_;
  Eigen::Vector3d offset_;
  Eigen::Matrix3d g_term_ = Eigen::Matrix3d::Zero();
};

/// A calibration applied to rows held in memory (a Recording read by
/// ReadLog or ReadLogRows): the accelerometer readings in the log's units to
/// m/s² (Corrector), and the gyroscope's to rad/s when the calibration has
/// one (GyroCorrector, with its g-sensitivity from the corrected specific
/// force). Logs of raw counts give SI readings this way.
class RecordingCorrector {
 public:
  /// \param log_units, log_gyro_units: the units the rows were read in (a
  ///   gyroscope read in deg/s is in rad/s once read).
  /// \throws mpcal::Error as Corrector and GyroCorrector, and (kUnits) for
  ///   a gyroscope in counts and a calibration without one.
  RecordingCorrector(const Calibration& calibration,
                     AccelUnits log_units,
                     GyroUnits log_gyro_units);
  /// The rows corrected: units m/s², the gyroscope (if any) in rad/s.
  Recording operator()(const Recording& rows) const;
  /// Whether the gyroscope is corrected (the calibration has one).
  bool corrects_gyro() const { return gyro_.has_value(); }

 private:
  Corrector accel_;
  std::optional<GyroCorrector> gyro_;
};

struct ApplyOptions {
  /// How to read the input log (columns, delimiters, units, time unit). Its
  /// `units` must match the calibration (CheckCalibrationApplies).
  LogOptions log;
  /// Units of the corrected accelerometer columns: kMps2 or kG. Empty: the
  /// input's units, except for raw counts, whose corrected values are written
  /// in m/s².
  std::optional<AccelUnits> out_units;
  /// Units of the corrected gyroscope columns (a calibration with a
  /// gyroscope, a log with gyroscope columns): kRadps or kDps. Empty: the
  /// log's units, except for raw counts, written in rad/s.
  std::optional<GyroUnits> out_gyro_units;
  /// A warning is given when the median corrected magnitude over the log's
  /// quietest stretches differs from the calibration's gravity by more than
  /// this fraction (wrong units or another sensor). 0.05 is far above what a
  /// right calibration leaves (< 0.5 %) and far below a g/m/s² mix-up.
  double rest_tolerance = 0.05;

  /// Empty string when valid, otherwise names the first bad field.
  std::string Validate() const;
};

/// What the magnitude at rest says when it is far from the calibration's
/// gravity (ApplyOptions::rest_tolerance).
enum class RestMismatchKind {
  /// Neither a g/m/s² mix-up: another sensor, or the wrong units.
  kSensorOrUnits,
  /// The raw readings at rest are about 1 read as m/s²: the log is in g.
  kLooksLikeG,
  /// The raw readings at rest are about 9.8 read as g: the log is in m/s².
  kLooksLikeMps2,
};

/// The finding of the magnitude-at-rest check: its kind, the figures, a
/// plain sentence (no flags), and the units to read the log in as advice
/// (LogOptions::units; an empty value when the data do not say which).
struct RestMismatch {
  RestMismatchKind kind = RestMismatchKind::kSensorOrUnits;
  double magnitude_mps2 = 0.0;
  double gravity_mps2 = 0.0;
  std::string what;
  Advice advice;
};

struct ApplyResult {
  std::size_t data_rows = 0;
  /// Comment, header and blank lines copied.
  std::size_t other_lines = 0;
  AccelUnits out_units = AccelUnits::kMps2;
  /// Whether the gyroscope columns were corrected too, the units they were
  /// read in (options.log's) and written in.
  bool gyro_corrected = false;
  GyroUnits log_gyro_units = GyroUnits::kRadps;
  GyroUnits out_gyro_units = GyroUnits::kRadps;
  /// Median corrected |a| (m/s²) over the quietest stretches of the log's
  /// start (up to about 260,000 rows); empty when the log has no rows.
  std::optional<double> rest_magnitude_mps2;
  /// For the user, one line each: the reader's (truncated last line, time
  /// unit).
  std::vector<std::string> warnings;
  /// The magnitude-at-rest check, when the magnitude is far from gravity.
  std::optional<RestMismatch> rest_mismatch;
};

/// Corrects the log `input` ("-": standard input) into `output` ("-":
/// standard output; otherwise written atomically).
/// \throws mpcal::Error for invalid options, a calibration that does not
///   apply to the log's units, `output` naming the input, any error of
///   LogScanner (no partial output file is left), or a write failure.
ApplyResult ApplyCalibration(const Calibration& calibration,
                             const std::string& input,
                             const std::string& output,
                             const ApplyOptions& options);

/// How a recording is corrected (ApplyCalibrationToBag).
struct BagApplyOptions {
  /// The sensor_msgs/Imu topic to correct; empty: the recording's only one.
  std::string topic;
  /// As ApplyOptions::rest_tolerance.
  double rest_tolerance = 0.05;
  /// White noise densities N per axis (a noise analysis's): when given, the
  /// covariance of each corrected vector is set to the variance of one
  /// sample, N²·f on the diagonal (f the topic's message rate, Hz), 0
  /// elsewhere; empty: the message's own covariance kept.
  std::optional<Eigen::Vector3d> accel_white_noise_mps2_per_rthz;
  std::optional<Eigen::Vector3d> gyro_white_noise_radps_per_rthz;
};

struct BagApplyResult {
  BagFormat format = BagFormat::kRos1;
  std::string topic;
  /// Messages of the topic corrected, and those left as they were because
  /// they mark the linear acceleration as not measured.
  std::int64_t corrected_messages = 0;
  std::int64_t unmeasured_messages = 0;
  /// Messages of the other topics, copied.
  std::int64_t other_messages = 0;
  /// Whether the angular velocity was corrected too (a calibration with a
  /// gyroscope, messages that measure it).
  bool gyro_corrected = false;
  /// The covariances written (BagApplyOptions' white noise), and the
  /// message rate they were set for; empty when the messages' own are kept.
  ImuCovariances covariances;
  std::optional<double> covariance_rate_hz;
  /// Chunk compressions written, as the input's.
  std::vector<std::string> compressions;
  std::optional<double> rest_magnitude_mps2;
  std::optional<RestMismatch> rest_mismatch;
  std::vector<std::string> warnings;
};

/// Corrects the sensor_msgs/Imu messages of a ROS 1 bag or an MCAP file into
/// `output`, a recording of the same kind written whole or not at all
/// (RewriteImuMessages in bag.h says what is copied): the linear
/// acceleration by the accelerometer's model (m/s² in, m/s² out, as
/// ApplyCalibration with a log in m/s²), the angular velocity by the
/// gyroscope's when the calibration has one (rad/s in and out). The
/// covariances are the input's (the calibration removes systematic errors
/// and leaves the noise the driver states as it was), or set from the white
/// noise given (BagApplyOptions).
/// \throws mpcal::Error for a calibration in counts (a recording is in m/s²
///   and rad/s), `output` naming the input, no sensor_msgs/Imu topic or
///   several with none chosen, a topic with no message (or, with a white
///   noise given, fewer than 2 or no time between its first and last), and as
///   RewriteImuMessages; no output file is then left.
BagApplyResult ApplyCalibrationToBag(const Calibration& calibration,
                                     const std::string& input,
                                     const std::string& output,
                                     const BagApplyOptions& options);

}  // namespace mpcal
