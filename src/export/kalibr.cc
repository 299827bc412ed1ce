// Kalibr's IMU YAML (imu.yaml): the noise model Kalibr's camera-IMU
// calibration reads, and its result with the scale-misalignment model.
#include <algorithm>
#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "export/formats.h"
#include "export/imu_chain.h"
#include "export/tool_yaml.h"
#include "export/triad.h"
#include "mpcal/error.h"
#include "mpcal/noise_file.h"

namespace mpcal::export_formats {
namespace {

void NoteBound(const KalibrFile& k,
               const KalibrValue& v,
               const char* key,
               std::vector<ExportNote>* notes) {
  if (!v.upper_bound) return;
  notes->push_back(
      ExportNote{ExportNoteKind::kUpperBound, key, k.Written(v), "", v.record_needed_s});
}

ExportedFile WriteKalibr(const ExportSources& s, const ExportOptions& o) {
  const KalibrFile k = KalibrYaml(s.noise->result, s.noise->input, o.rostopic, o.inflate);
  ExportedFile out;
  out.text = k.text;
  NoteBound(k, k.accel_noise_density, "accelerometer_noise_density", &out.notes);
  NoteBound(k, k.accel_random_walk, "accelerometer_random_walk", &out.notes);
  NoteBound(k, k.gyro_noise_density, "gyroscope_noise_density", &out.notes);
  NoteBound(k, k.gyro_random_walk, "gyroscope_random_walk", &out.notes);
  return out;
}

}  // namespace

ExportFormat Kalibr() {
  ExportFormat f;
  f.name = "kalibr";
  f.file = "Kalibr imu.yaml";
  f.noise = ExportNeed::kRequired;
  f.write = WriteKalibr;
  return f;
}

}  // namespace mpcal::export_formats

// Kalibr's IMU result with the scale-misalignment model
// (kalibr_calibrate_imu_camera --imu-models scale-misalignment): the noise
// keys, T_i_b, time_offset, and the intrinsics under accelerometers and
// gyroscopes, as ImuSetParameters writes them (ConfigReader.py).
namespace mpcal::export_formats {
namespace {

ExportedFile WriteKalibrScaleMisalignment(const ExportSources& s,
                                          const ExportOptions& o) {
  const KalibrIntrinsics k = IntrinsicsOf(*s.calibration);
  ExportedFile out;
  out.text = IntrinsicsHeader(s, "Kalibr IMU intrinsics, model scale-misalignment");
  out.text +=
      "# Kalibr's model (IccSensors.py, IccScaledMisalignedImu): a_meas = M_a*a + b_a,\n"
      "# w_meas = M_g*C_gyro_i*w + A*C_gyro_i*a + b_g; M lower triangular, C_gyro_i a\n"
      "# rotation, A in (rad/s)/(m/s^2).\n";
  out.text += "imu0:\n";
  out.text += YamlMatrixLines("T_i_b", Eigen::Matrix4d::Identity(), 2);
  out.text += NoiseKeyLines(s, o, 2, &out.notes);
  out.text += "  model: scale-misalignment\n  accelerometers:\n";
  out.text += YamlMatrixLines("M", k.accel_m, 4);
  out.text += "  gyroscopes:\n";
  out.text += YamlMatrixLines("M", k.gyro_m, 4);
  out.text += YamlMatrixLines("A", k.a_radps_per_mps2, 4);
  out.text += YamlMatrixLines("C_gyro_i", k.c_gyro_i, 4);
  AddBiasNotes(k, &out.notes);
  return out;
}

ImportedCalibration ReadKalibrScaleMisalignment(const std::vector<ImportFile>& files,
                                                const ImportOptions& o) {
  const ImportFile& f = files.front();
  const YAML::Node imu = ImuBlock(LoadToolYaml(f), f);
  const std::string model = YamlString(imu, "model", "imu0", f);
  ImportedCalibration out;
  if (model != "scale-misalignment" && model != "scale-misalignment-size-effect") {
    throw Error(
        ErrorKind::kInput,
        fmt::format("'{}': imu0.model is '{}'; only Kalibr's scale-misalignment "
                    "models hold intrinsics (an imu.yaml of model 'calibrated' has "
                    "none)",
                    f.path,
                    model));
  }
  const YAML::Node accel = imu["accelerometers"];
  const YAML::Node gyro = imu["gyroscopes"];
  if (!accel || !accel.IsMap() || !gyro || !gyro.IsMap()) {
    throw Error(ErrorKind::kInput,
                fmt::format("'{}': imu0.accelerometers and imu0.gyroscopes must be maps "
                            "holding M (and A, C_gyro_i)",
                            f.path));
  }
  KalibrIntrinsics k;
  k.accel_m = YamlMatrix3(accel, "M", "imu0.accelerometers", f);
  k.gyro_m = YamlMatrix3(gyro, "M", "imu0.gyroscopes", f);
  k.a_radps_per_mps2 = YamlMatrix3(gyro, "A", "imu0.gyroscopes", f);
  k.c_gyro_i = YamlMatrix3(gyro, "C_gyro_i", "imu0.gyroscopes", f);
  const std::string at = fmt::format("'{}': imu0.", f.path);
  CheckTriangular(k.accel_m, true, at + "accelerometers.M");
  CheckTriangular(k.gyro_m, true, at + "gyroscopes.M");
  CheckInvertible(k.accel_m, at + "accelerometers.M");
  CheckInvertible(k.gyro_m, at + "gyroscopes.M");
  CheckRotation(k.c_gyro_i, at + "gyroscopes.C_gyro_i");
  for (const auto& [m, key] : {std::pair{&k.accel_m, "accelerometers.M"},
                               std::pair{&k.gyro_m, "gyroscopes.M"}}) {
    if ((*m)(0, 0) <= 0.0 || (*m)(1, 1) <= 0.0 || (*m)(2, 2) <= 0.0) {
      throw Error(
          ErrorKind::kInput,
          fmt::format("{}{}: a diagonal entry is not positive; an axis would read "
                      "backwards",
                      at,
                      key));
    }
  }
  k.accel_bias_mps2.setZero();
  k.gyro_bias_radps.setZero();
  out.calibration = CalibrationOf(k, o.gravity_mps2);
  out.calibration.imported_from = "Kalibr imu.yaml (scale-misalignment)";
  out.notes.push_back(ExportNote{ExportNoteKind::kNotMeasured,
                                 "the biases (Kalibr's result has none)",
                                 0.0,
                                 "",
                                 {}});
  if (model == "scale-misalignment-size-effect") {
    double arm_m = 0.0;
    for (const char* key : {"rx_i", "ry_i", "rz_i"}) {
      const YAML::Node r = accel[key];
      if (!r || !r.IsSequence()) continue;
      for (const auto& v : r) {
        double x = 0.0;
        if (v.IsScalar() && YAML::convert<double>::decode(v, x)) {
          arm_m = std::max(arm_m, std::abs(x));
        }
      }
    }
    out.notes.push_back(
        ExportNote{ExportNoteKind::kTermDropped,
                   "the size effect (accelerometer lever arms rx_i, ry_i, "
                   "rz_i)",
                   arm_m,
                   "m",
                   {}});
  }
  return out;
}

}  // namespace

ExportFormat KalibrScaleMisalignment() {
  ExportFormat f;
  f.name = "kalibr-scale-misalignment";
  f.file = "Kalibr imu.yaml, model scale-misalignment";
  f.calibration = ExportNeed::kRequired;
  f.noise = ExportNeed::kRequired;
  f.needs_gyroscope = true;
  f.write = WriteKalibrScaleMisalignment;
  f.read = ReadKalibrScaleMisalignment;
  f.import_files = "IMU.yaml";
  return f;
}

}  // namespace mpcal::export_formats
