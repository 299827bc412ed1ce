// mpcal's calibration as Kalibr's scale-misalignment intrinsics and back.
#include "export/imu_chain.h"

#include <fmt/format.h>
#include <Eigen/Dense>

#include "export/triad.h"
#include "mpcal/error.h"

namespace mpcal::export_formats {

KalibrIntrinsics IntrinsicsOf(const Calibration& c) {
  const GyroCalibration& g = *c.gyroscope;
  KalibrIntrinsics k;
  // a = T·D·(α − b)  =>  α = (T·D)⁻¹·a + b.
  const Eigen::Matrix3d td = c.Affine().linear / c.mps2_per_unit;
  k.accel_m = td.inverse();
  // Exactly lower triangular (the inverse of a lower-triangular matrix is).
  k.accel_m(0, 1) = k.accel_m(0, 2) = k.accel_m(1, 2) = 0.0;
  k.accel_bias_mps2 = c.model.bias_mps2;
  // ω = M·(ω_m − b − G·a)  =>  ω_m = M⁻¹·ω + G·a + b, and M⁻¹ = M_g·C.
  if (g.m.determinant() <= 0.0) {
    throw Error(ErrorKind::kInput,
                "the gyroscope's M mirrors the axes (negative determinant); no rotation "
                "C_gyro_i can hold it");
  }
  const Factored f = LowerTimesRotation(g.m.inverse());
  k.gyro_m = f.triangular;
  k.gyro_m(0, 1) = k.gyro_m(0, 2) = k.gyro_m(1, 2) = 0.0;
  k.c_gyro_i = f.rotation;
  const Eigen::Matrix3d gs =
      g.g_sensitivity_radps_per_mps2.value_or(Eigen::Matrix3d::Zero());
  k.a_radps_per_mps2 = gs * f.rotation.transpose();
  k.gyro_bias_radps = g.bias_radps;
  return k;
}

Calibration CalibrationOf(const KalibrIntrinsics& k, double gravity_mps2) {
  Calibration c;
  c.gravity_mps2 = gravity_mps2;
  c.input_units = AccelUnits::kMps2;
  c.mps2_per_unit = 1.0;
  const Eigen::Matrix3d linear = k.accel_m.inverse();
  c.model = ModelOfLower(linear, k.accel_bias_mps2, 1.0);
  GyroCalibration g;
  g.input_units = GyroUnits::kRadps;
  g.radps_per_unit = 1.0;
  g.m = k.c_gyro_i.transpose() * k.gyro_m.inverse();
  g.bias_radps = k.gyro_bias_radps;
  if (!k.a_radps_per_mps2.isZero(0.0))
    g.g_sensitivity_radps_per_mps2 = k.a_radps_per_mps2 * k.c_gyro_i;
  c.gyroscope = g;
  return c;
}

void AddBiasNotes(const KalibrIntrinsics& k, std::vector<ExportNote>* notes) {
  notes->push_back(ExportNote{ExportNoteKind::kCommentOnly,
                              "the accelerometer's bias",
                              k.accel_bias_mps2.cwiseAbs().maxCoeff(),
                              "m/s^2",
                              {}});
  notes->push_back(ExportNote{ExportNoteKind::kCommentOnly,
                              "the gyroscope's bias",
                              k.gyro_bias_radps.cwiseAbs().maxCoeff(),
                              "rad/s",
                              {}});
}

std::string IntrinsicsHeader(const ExportSources& s, const char* what) {
  const Calibration& c = *s.calibration;
  const GyroCalibration& g = *c.gyroscope;
  std::string out = fmt::format("# {}, written by mpcal from '{}' and '{}'.\n",
                                what,
                                s.calibration_path,
                                s.noise_path);
  out += fmt::format(
      "# Readings in m/s^2 and rad/s: the log's {} times {} (accelerometer) and its {} "
      "times {} (gyroscope).\n",
      ToString(c.input_units),
      c.mps2_per_unit,
      ToString(g.input_units),
      g.radps_per_unit);
  out +=
      "# Frame: mpcal's (x along the accelerometer's x axis, y in the plane of its x\n"
      "# and y axes), the frame a lower-triangular accelerometer M means.\n";
  out += fmt::format(
      "# Biases (not keys of this file; the filter estimates its own): accelerometer "
      "[{}, {}, {}] m/s^2, gyroscope [{}, {}, {}] rad/s.\n",
      c.model.bias_mps2.x(),
      c.model.bias_mps2.y(),
      c.model.bias_mps2.z(),
      g.bias_radps.x(),
      g.bias_radps.y(),
      g.bias_radps.z());
  return out;
}

}  // namespace mpcal::export_formats
