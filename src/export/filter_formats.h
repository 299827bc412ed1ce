// The formats of the filters' noise files (filter_noise.cc) and of the
// autopilots' parameters (autopilot_params.cc), each its registry entry, and
// the figures of what an autopilot's model drops, for the tests.
//
// Each file follows its tool's own reading code, cited in the file's
// comments and in docs/export/: the keys, the units and whether a density is
// continuous or per sample. The densities of noise.h are continuous-time (N
// in u/√Hz, K in u/s/√Hz): a white noise sampled at f Hz has σ = N·√f per
// sample, a random walk steps by K/√f.
#pragma once

#include <optional>

#include "mpcal/calibration.h"
#include "mpcal/export.h"

namespace mpcal::export_formats {

/// ORB-SLAM3's IMU settings (IMU.NoiseGyro, IMU.NoiseAcc, IMU.GyroWalk,
/// IMU.AccWalk, IMU.Frequency): continuous-time densities, as ORB-SLAM3
/// reads them; the largest axis of each sensor (KalibrYaml's rule).
ExportFormat OrbSlam3();
/// VINS-Mono / VINS-Fusion's acc_n, gyr_n, acc_w, gyr_w: per sample, so
/// that the covariance its preintegration propagates grows as the sensor's
/// does: acc_n = N·√(2f), acc_w = K·√f.
ExportFormat Vins();
/// KF-GINS's imunoise block: arw, vrw per axis, gbstd and abstd from the
/// bias instability B, corrtime T = 2B²/K² (the shortest over the axes).
ExportFormat KfGins();
/// sensor_msgs/Imu covariances: σ² per sample = N²·f on the diagonal.
ExportFormat RosImu();
/// PX4's CAL_ACC0_*OFF, CAL_ACC0_*SCALE, CAL_GYRO0_*OFF in QGroundControl's
/// parameter file; read back as a bias-scale-6 calibration.
ExportFormat Px4();
/// ArduPilot's INS_ACCOFFS_*, INS_ACCSCAL_*, INS_GYROFFS_* as NAME,VALUE
/// lines; read back as a bias-scale-6 calibration.
ExportFormat ArduPilot();

}  // namespace mpcal::export_formats

namespace mpcal {

/// What an autopilot's model (accelerometer offset and scale per axis,
/// gyroscope offset) drops of a calibration, for this sensor.
struct AutopilotLoss {
  /// Largest difference between mpcal's corrected specific force and the
  /// autopilot's over every direction of a specific force of the
  /// calibration's gravity (m/s²), and the largest angle between the two
  /// (rad): the non-orthogonality T.
  double accel_max_error_mps2 = 0.0;
  double accel_max_tilt_rad = 0.0;
  /// Largest |(I − M⁻¹) ω| / |ω| over directions: the gyroscope's scale,
  /// misalignment and rotation, as a fraction of the rate. Unset without a
  /// gyroscope.
  std::optional<double> gyro_max_relative_error;
  /// The g-sensitivity's largest rate error at the calibration's gravity
  /// (rad/s), when the calibration models it.
  std::optional<double> gyro_g_sensitivity_radps;
};

/// The loss of `calibration` in an autopilot's model.
AutopilotLoss AutopilotModelLoss(const Calibration& calibration);

}  // namespace mpcal
