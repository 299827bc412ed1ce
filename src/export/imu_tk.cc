// imu_tk's .calib (Pretto; Kyle-ak/imu_tk include/imu_tk/calibration.h,
// CalibratedTriad_): 21 numbers, T (3×3, row-major), K (3×3 diagonal), B
// (3), read by CalibratedTriad_::load with `>>` and applied as
// X' = T·K·(X − B) to raw readings X. The accelerometer's T is upper
// unit-triangular (calibrateAcc fixes its lower entries at zero): its frame
// keeps the sensor's z axis, where mpcal's keeps x, and the two differ by
// the rotation R of L = R·U (L mpcal's lower-triangular correction, U =
// T·K). The gyroscope's T is general with a unit diagonal, in the
// accelerometer's frame.
#include <cmath>
#include <string>
#include <vector>

#include <fast_float/fast_float.h>
#include <fmt/format.h>
#include <Eigen/Dense>

#include "export/formats.h"
#include "export/triad.h"
#include "mpcal/error.h"

namespace mpcal::export_formats {
namespace {

struct ImuTkTriad {
  Eigen::Matrix3d t;
  Eigen::Vector3d k;
  Eigen::Vector3d b;
};

// The 21 numbers of a .calib; after them only blank lines and lines
// starting with '#' (comments; imu_tk's loader stops after the 21st number).
ImuTkTriad ParseImuTk(const ImportFile& f) {
  std::vector<double> v;
  const char* p = f.text.data();
  const char* end = p + f.text.size();
  int line = 1;
  while (p < end) {
    const char c = *p;
    if (c == '\n') ++line;
    if (c == ' ' || c == '\t' || c == '\n' || c == '\r') {
      ++p;
      continue;
    }
    if (c == '#' && v.size() == 21) {
      while (p < end && *p != '\n') ++p;
      continue;
    }
    if (v.size() == 21) {
      throw Error(
          ErrorKind::kInput,
          fmt::format("'{}' line {}: text after the 21 numbers of an imu_tk .calib "
                      "(T, K, B); only '#' comments may follow",
                      f.path,
                      line));
    }
    double x = 0.0;
    const auto r = fast_float::from_chars(p, end, x);
    if (r.ec != std::errc() || !std::isfinite(x)) {
      const char* stop = p;
      while (stop < end && *stop != ' ' && *stop != '\n' && *stop != '\t' &&
             *stop != '\r' && stop - p < 20) {
        ++stop;
      }
      throw Error(
          ErrorKind::kInput,
          fmt::format("'{}' line {}: '{}' is not a finite number; an imu_tk .calib "
                      "holds 21 numbers (T 3×3, K 3×3, B 3)",
                      f.path,
                      line,
                      std::string(p, stop)));
    }
    v.push_back(x);
    p = r.ptr;
  }
  if (v.size() != 21) {
    throw Error(ErrorKind::kInput,
                fmt::format("'{}' holds {} numbers; an imu_tk .calib holds 21 (T 3×3, K "
                            "3×3, B 3)",
                            f.path,
                            v.size()));
  }
  ImuTkTriad t;
  Eigen::Matrix3d k;
  for (std::size_t i = 0; i < 9; ++i) {
    const auto r = static_cast<int>(i / 3);
    const auto c = static_cast<int>(i % 3);
    t.t(r, c) = v[i];
    k(r, c) = v[9 + i];
  }
  for (std::size_t i = 0; i < 3; ++i) t.b[static_cast<int>(i)] = v[18 + i];
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      if (i != j && k(i, j) != 0.0) {
        throw Error(ErrorKind::kInput,
                    fmt::format("'{}': K, the scale matrix, has {:.6g} off its diagonal "
                                "(entry {}, {}); imu_tk's K is diagonal",
                                f.path,
                                k(i, j),
                                i + 1,
                                j + 1));
      }
    }
    t.k[i] = k(i, i);
  }
  CheckInvertible(t.t * t.k.asDiagonal(), fmt::format("'{}': T·K", f.path));
  return t;
}

// Rows of a matrix or a column vector as Eigen prints them for imu_tk,
// with every digit a double needs.
void PutMatrix(std::string* out, const Eigen::MatrixXd& m) {
  for (Eigen::Index i = 0; i < m.rows(); ++i) {
    for (Eigen::Index j = 0; j < m.cols(); ++j) {
      // + 0.0: a negative zero is written as 0.
      *out += fmt::format("{}{:.17g}", j == 0 ? "" : " ", m(i, j) + 0.0);
    }
    *out += "\n";
  }
  *out += "\n";
}

// "[r11, r12, ..., r33]" with every digit.
std::string RowMajorList(const Eigen::Matrix3d& m) {
  std::string out = "[";
  for (int i = 0; i < 9; ++i) {
    out += fmt::format("{}{:.17g}", i == 0 ? "" : ", ", m(i / 3, i % 3));
  }
  return out + "]";
}

std::string CalibText(const ImuTkTriad& t, const std::vector<std::string>& comments) {
  std::string out;
  PutMatrix(&out, t.t);
  PutMatrix(&out, Eigen::Matrix3d(t.k.asDiagonal()));
  PutMatrix(&out, t.b);
  for (const std::string& c : comments) out += "# " + c + "\n";
  return out;
}

// T·K = U split into a unit-diagonal T and the diagonal K (column scales).
ImuTkTriad Split(const Eigen::Matrix3d& u, const Eigen::Vector3d& b) {
  ImuTkTriad t;
  t.k = u.diagonal();
  t.t = u * t.k.cwiseInverse().asDiagonal();
  t.b = b;
  return t;
}

ExportedFile WriteImuTkAccel(const ExportSources& s, const ExportOptions&) {
  const Calibration& c = *s.calibration;
  const AccelAffine a = AccelOf(c);
  const Factored f = RotationTimesUpper(a.linear);
  ExportedFile out;
  const double angle = RotationAngle(f.rotation);
  out.text = CalibText(
      Split(f.triangular, a.offset),
      {fmt::format(
           "imu_tk accelerometer calibration (T, K, B), written by mpcal from '{}'",
           s.calibration_path),
       fmt::format("X' = T*K*(X - B): X raw ({}), X' in m/s^2 (gravity {} m/s^2)",
                   ToString(c.input_units),
                   c.gravity_mps2),
       std::string("T is upper unit-triangular: the frame keeps the sensor's z axis "
                   "(mpcal's keeps x)."),
       fmt::format(
           "X' = R^T a, a mpcal's corrected output; R (rotation by {:.6g} rad) = ",
           angle),
       RowMajorList(f.rotation)});
  out.notes.push_back(ExportNote{
      ExportNoteKind::kFrameRotated, "imu_tk accelerometer frame", angle, "rad", {}});
  return out;
}

ExportedFile WriteImuTkGyro(const ExportSources& s, const ExportOptions&) {
  const Calibration& c = *s.calibration;
  const GyroCalibration& g = *c.gyroscope;
  const Factored f = RotationTimesUpper(AccelOf(c).linear);
  // ω_imu_tk = Rᵀ ω = Rᵀ·M·u·(r − b/u).
  const Eigen::Matrix3d u = f.rotation.transpose() * g.m * g.radps_per_unit;
  ExportedFile out;
  const double angle = RotationAngle(f.rotation);
  out.text = CalibText(
      Split(u, g.bias_radps / g.radps_per_unit),
      {fmt::format("imu_tk gyroscope calibration (T, K, B), written by mpcal from '{}'",
                   s.calibration_path),
       fmt::format(
           "X' = T*K*(X - B): X raw ({}), X' in rad/s, in the frame of the imu_tk "
           "accelerometer file written from the same calibration",
           ToString(g.input_units)),
       fmt::format(
           "X' = R^T w, w mpcal's corrected output; R (rotation by {:.6g} rad) = ",
           angle),
       RowMajorList(f.rotation)});
  out.notes.push_back(ExportNote{
      ExportNoteKind::kFrameRotated, "imu_tk gyroscope frame", angle, "rad", {}});
  if (g.g_sensitivity_radps_per_mps2) {
    out.notes.push_back(ExportNote{ExportNoteKind::kTermDropped,
                                   "the gyroscope's g-sensitivity",
                                   g.g_sensitivity_radps_per_mps2->cwiseAbs().maxCoeff(),
                                   "rad/s per m/s^2",
                                   {}});
  }
  return out;
}

// The nominal factor of raw counts: the geometric mean of the diagonal, so
// that the scale-factor errors are relative to the sensor's own scale.
double NominalFactor(const Eigen::Vector3d& diagonal) {
  return std::cbrt(std::abs(diagonal.prod()));
}

void ImportAccel(const ImportFile& f, const ImportOptions& o, Calibration* c) {
  const ImuTkTriad t = ParseImuTk(f);
  const Factored q = RotationTimesLower(t.t * t.k.asDiagonal());
  // U = Q·L: mpcal's L, and its frame is Qᵀ times imu_tk's.
  const Eigen::Matrix3d& l = q.triangular;
  if (q.rotation.determinant() < 0.0) {
    throw Error(ErrorKind::kInput,
                fmt::format("'{}': T·K mirrors the axes (negative determinant); a "
                            "calibration keeps a right-handed triad",
                            f.path));
  }
  c->input_units = o.accel_units;
  c->mps2_per_unit =
      FixedMps2PerUnit(o.accel_units)
          .value_or(o.mps2_per_count.value_or(NominalFactor(l.diagonal())));
  c->gravity_mps2 = o.gravity_mps2;
  c->model = ModelOfLower(l, t.b, c->mps2_per_unit);
  c->model_kind = ModelKind::kShinElSheimy9;
}

void ImportGyro(const ImportFile& f,
                const ImportFile& accel,
                const ImportOptions& o,
                Calibration* c) {
  const ImuTkTriad a = ParseImuTk(accel);
  const Factored q = RotationTimesLower(a.t * a.k.asDiagonal());
  const ImuTkTriad t = ParseImuTk(f);
  GyroCalibration g;
  g.input_units = o.gyro_units;
  g.radps_per_unit = FixedRadpsPerUnit(o.gyro_units)
                         .value_or(o.radps_per_count.value_or(NominalFactor(t.k)));
  g.m = q.rotation.transpose() * t.t * t.k.asDiagonal() / g.radps_per_unit;
  g.bias_radps = t.b * g.radps_per_unit;
  c->gyroscope = g;
}

ImportedCalibration ReadImuTk(const std::vector<ImportFile>& files,
                              const ImportOptions& o) {
  ImportedCalibration out;
  Calibration& c = out.calibration;
  ImportAccel(files[0], o, &c);
  if (files.size() > 1) ImportGyro(files[1], files[0], o, &c);
  c.imported_from = "imu_tk .calib";
  return out;
}

}  // namespace

ExportFormat ImuTk() {
  ExportFormat f;
  f.name = "imu-tk";
  f.file = "imu_tk .calib, accelerometer and gyroscope";
  f.read = ReadImuTk;
  f.min_files = 1;
  f.max_files = 2;
  f.import_files = "ACCEL.calib [GYRO.calib]";
  return f;
}

ExportFormat ImuTkAccel() {
  ExportFormat f;
  f.name = "imu-tk-accel";
  f.file = "imu_tk accelerometer .calib";
  f.calibration = ExportNeed::kRequired;
  f.write = WriteImuTkAccel;
  return f;
}

ExportFormat ImuTkGyro() {
  ExportFormat f;
  f.name = "imu-tk-gyro";
  f.file = "imu_tk gyroscope .calib";
  f.calibration = ExportNeed::kRequired;
  f.needs_gyroscope = true;
  f.write = WriteImuTkGyro;
  return f;
}

}  // namespace mpcal::export_formats
