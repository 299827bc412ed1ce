// OpenVINS's kalibr_imu_chain.yaml (rpng/open_vins): the noise keys Kalibr
// defined and the IMU intrinsics OpenVINS reads back
// (ov_msckf/src/core/VioManagerOptions.h: Tw, Ta, R_IMUtoGYRO, R_IMUtoACC,
// Tg; ov_msckf/src/state/StateOptions.h: model) and applies in its
// propagator (ov_msckf/src/state/Propagator.cpp):
//   a = R_IMUtoACCᵀ·Ta⁻¹·(a_m − b_a)
//   w = R_IMUtoGYROᵀ·Tw⁻¹·(w_m − b_g − Tg·a)
// With model "kalibr" OpenVINS keeps the lower triangle of Tw⁻¹ and Ta⁻¹,
// with "rpng" the upper.
#include <cmath>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <Eigen/Dense>

#include "export/formats.h"
#include "export/imu_chain.h"
#include "export/tool_yaml.h"
#include "export/triad.h"
#include "mpcal/error.h"

namespace mpcal::export_formats {
namespace {

ExportedFile WriteOpenVins(const ExportSources& s, const ExportOptions& o) {
  const KalibrIntrinsics k = IntrinsicsOf(*s.calibration);
  ExportedFile out;
  out.text = "%YAML:1.0\n";
  out.text += IntrinsicsHeader(s, "OpenVINS IMU chain (kalibr_imu_chain.yaml)");
  out.text +=
      "# OpenVINS applies (Propagator.cpp): a = R_IMUtoACC^T*Ta^-1*(a_m - b_a),\n"
      "# w = R_IMUtoGYRO^T*Tw^-1*(w_m - b_g - Tg*a); model kalibr: Tw, Ta lower "
      "triangular.\n"
      "# Tg multiplies a in the IMU frame (Kalibr's A multiplies it in the gyroscope's:\n"
      "# Tg = A*C_gyro_i).\n";
  out.text += "imu0:\n";
  out.text += YamlMatrixLines("T_i_b", Eigen::Matrix4d::Identity(), 2);
  out.text += NoiseKeyLines(s, o, 2, &out.notes);
  out.text += "  model: kalibr\n";
  out.text += YamlMatrixLines("Tw", k.gyro_m, 2);
  out.text += YamlMatrixLines("R_IMUtoGYRO", k.c_gyro_i, 2);
  out.text += YamlMatrixLines("Ta", k.accel_m, 2);
  out.text += YamlMatrixLines("R_IMUtoACC", Eigen::Matrix3d::Identity(), 2);
  out.text += YamlMatrixLines("Tg", k.a_radps_per_mps2 * k.c_gyro_i, 2);
  AddBiasNotes(k, &out.notes);
  return out;
}

// The map under `key`, or the identity (zero for Tg) when absent: OpenVINS
// starts from those (VioManagerOptions.h).
Eigen::Matrix3d OrDefault(const YAML::Node& imu,
                          const char* key,
                          const Eigen::Matrix3d& fallback,
                          const ImportFile& f) {
  return imu[key] ? YamlMatrix3(imu, key, "imu0", f) : fallback;
}

ImportedCalibration ReadOpenVins(const std::vector<ImportFile>& files,
                                 const ImportOptions& o) {
  const ImportFile& f = files.front();
  const YAML::Node imu = ImuBlock(LoadToolYaml(f), f);
  const std::string model = imu["model"] ? YamlString(imu, "model", "imu0", f) : "kalibr";
  if (model != "kalibr" && model != "calibrated" && model != "rpng") {
    throw Error(
        ErrorKind::kInput,
        fmt::format("'{}': imu0.model is '{}'; OpenVINS knows kalibr, calibrated and "
                    "rpng",
                    f.path,
                    model));
  }
  if (!imu["Tw"] && !imu["Ta"]) {
    throw Error(
        ErrorKind::kInput,
        fmt::format("'{}': imu0 has neither Tw nor Ta; a file without intrinsics is "
                    "an ideal IMU, nothing to import",
                    f.path));
  }
  const Eigen::Matrix3d id = Eigen::Matrix3d::Identity();
  const Eigen::Matrix3d tw = OrDefault(imu, "Tw", id, f);
  const Eigen::Matrix3d ta = OrDefault(imu, "Ta", id, f);
  const Eigen::Matrix3d r_acc = OrDefault(imu, "R_IMUtoACC", id, f);
  const Eigen::Matrix3d r_gyro = OrDefault(imu, "R_IMUtoGYRO", id, f);
  const Eigen::Matrix3d tg = OrDefault(imu, "Tg", Eigen::Matrix3d::Zero(), f);
  const std::string at = fmt::format("'{}': imu0.", f.path);
  CheckInvertible(tw, at + "Tw");
  CheckInvertible(ta, at + "Ta");
  CheckRotation(r_acc, at + "R_IMUtoACC");
  CheckRotation(r_gyro, at + "R_IMUtoGYRO");
  // OpenVINS keeps one triangle of the inverses: the other must be empty,
  // or OpenVINS would not apply the matrix the file holds.
  const bool lower = model != "rpng";
  CheckTriangular(ta.inverse(), lower, at + "Ta (its inverse, as OpenVINS keeps it)");
  CheckTriangular(tw.inverse(), lower, at + "Tw (its inverse, as OpenVINS keeps it)");
  // a_ov = R_accᵀ·Ta⁻¹·(a_m − b) = Q·L·(a_m − b): mpcal's a = L·(a_m − b) and
  // a_ov = Q·a.
  const Factored q = RotationTimesLower(r_acc.transpose() * ta.inverse());
  ImportedCalibration out;
  Calibration& c = out.calibration;
  c.gravity_mps2 = o.gravity_mps2;
  c.model = ModelOfLower(q.triangular, Eigen::Vector3d::Zero(), 1.0);
  GyroCalibration g;
  g.m = q.rotation.transpose() * r_gyro.transpose() * tw.inverse();
  if (!tg.isZero(0.0)) g.g_sensitivity_radps_per_mps2 = tg * q.rotation;
  c.gyroscope = g;
  c.imported_from = "OpenVINS kalibr_imu_chain.yaml";
  const double angle = RotationAngle(q.rotation);
  if (angle > 1e-12) {
    out.notes.push_back(ExportNote{
        ExportNoteKind::kFrameRotated, "OpenVINS's IMU frame", angle, "rad", {}});
  }
  out.notes.push_back(ExportNote{ExportNoteKind::kNotMeasured,
                                 "the biases (OpenVINS's file has none)",
                                 0.0,
                                 "",
                                 {}});
  return out;
}

}  // namespace

ExportFormat OpenVins() {
  ExportFormat f;
  f.name = "openvins";
  f.file = "OpenVINS kalibr_imu_chain.yaml";
  f.calibration = ExportNeed::kRequired;
  f.noise = ExportNeed::kRequired;
  f.needs_gyroscope = true;
  f.write = WriteOpenVins;
  f.read = ReadOpenVins;
  f.import_files = "kalibr_imu_chain.yaml";
  return f;
}

}  // namespace mpcal::export_formats
