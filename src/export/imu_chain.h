// The IMU intrinsics that Kalibr's scale-misalignment model and OpenVINS
// hold, from mpcal's calibration and back (kalibr.cc, openvins.cc).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "mpcal/calibration.h"
#include "mpcal/export.h"

namespace mpcal::export_formats {

/// Kalibr's scale-misalignment model (IccSensors.py, IccScaledMisalignedImu):
///   accelerometer  α = M_a·a + b_a            (M_a lower triangular)
///   gyroscope      ω_m = M_g·C·ω + A·C·a + b_g (M_g lower triangular, C a rotation)
/// with a and ω in mpcal's frame, α and ω_m the readings in m/s² and rad/s
/// (mpcal's readings times its nominal factors).
struct KalibrIntrinsics {
  Eigen::Matrix3d accel_m;
  Eigen::Vector3d accel_bias_mps2;
  Eigen::Matrix3d gyro_m;
  Eigen::Matrix3d c_gyro_i;
  Eigen::Matrix3d a_radps_per_mps2;
  Eigen::Vector3d gyro_bias_radps;
};

/// From mpcal's calibration (which must have its gyroscope).
/// \throws mpcal::Error when the gyroscope's M mirrors the axes.
KalibrIntrinsics IntrinsicsOf(const Calibration& c);

/// Back to a calibration in m/s² and rad/s (no 1σ).
Calibration CalibrationOf(const KalibrIntrinsics& k, double gravity_mps2);

/// The biases, which Kalibr's and OpenVINS's files have no key for
/// (written in a comment; the filter estimates its own): one note each.
void AddBiasNotes(const KalibrIntrinsics& k, std::vector<ExportNote>* notes);

/// The comment lines every intrinsics file opens with: where it came from,
/// the readings' units and what the nominal factors are.
std::string IntrinsicsHeader(const ExportSources& s, const char* what);

}  // namespace mpcal::export_formats
