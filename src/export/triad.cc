// Matrix factorisations between mpcal's model and the tools' matrices.
#include "export/triad.h"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>
#include <Eigen/Dense>

#include "mpcal/error.h"

namespace mpcal::export_formats {
namespace {

// The triangular factor's diagonal made positive: the sign moves into the
// rotation's columns, R·U = (R·S)·(S·U) with S = S⁻¹ diagonal of ±1.
Factored PositiveDiagonal(const Eigen::Matrix3d& q, const Eigen::Matrix3d& t) {
  Eigen::Vector3d s;
  for (int i = 0; i < 3; ++i) s[i] = t(i, i) < 0.0 ? -1.0 : 1.0;
  return {q * s.asDiagonal(), s.asDiagonal() * t};
}

// The exchange matrix J (ones on the anti-diagonal): J·L·J is upper
// triangular for a lower triangular L.
Eigen::Matrix3d Exchange() {
  Eigen::Matrix3d j = Eigen::Matrix3d::Zero();
  j(0, 2) = j(1, 1) = j(2, 0) = 1.0;
  return j;
}

}  // namespace

Factored RotationTimesUpper(const Eigen::Matrix3d& m) {
  const Eigen::HouseholderQR<Eigen::Matrix3d> qr(m);
  const Eigen::Matrix3d q = qr.householderQ();
  const Eigen::Matrix3d r = qr.matrixQR().triangularView<Eigen::Upper>();
  return PositiveDiagonal(q, r);
}

Factored RotationTimesLower(const Eigen::Matrix3d& m) {
  // J m J = Q U  =>  m = (J Q J)(J U J), J U J lower triangular.
  const Eigen::Matrix3d j = Exchange();
  const Factored f = RotationTimesUpper(j * m * j);
  return {j * f.rotation * j, j * f.triangular * j};
}

Factored LowerTimesRotation(const Eigen::Matrix3d& m) {
  // mᵀ = Q U  =>  m = Uᵀ Qᵀ.
  const Factored f = RotationTimesUpper(m.transpose());
  return {f.rotation.transpose(), f.triangular.transpose()};
}

double RotationAngle(const Eigen::Matrix3d& r) {
  return std::acos(std::clamp((r.trace() - 1.0) / 2.0, -1.0, 1.0));
}

AccelAffine AccelOf(const Calibration& c) {
  const Calibration::AffineCorrection a = c.Affine();
  // a = linear·r + o = linear·(r − offset) with offset = −linear⁻¹·o.
  return {a.linear, -a.linear.inverse() * a.offset};
}

ErrorModel ModelOfLower(const Eigen::Matrix3d& linear,
                        const Eigen::Vector3d& offset,
                        double mps2_per_unit) {
  // linear/u = T·D with D = diag(1/(1+s)); T as model.h writes it.
  const Eigen::Matrix3d td = linear / mps2_per_unit;
  ErrorModel m;
  const double dx = td(0, 0);
  const double tyz = td(1, 0) / dx;
  m.theta_yz_rad = std::atan(tyz);
  const double dy = td(1, 1) * std::cos(m.theta_yz_rad);
  const double tzx = td(2, 1) * std::cos(m.theta_yz_rad) / dy;
  m.theta_zx_rad = std::atan(tzx);
  // td(2,0)/dx = tan θzx tan θyz − tan θzy / cos θzx.
  const double tzy = (tzx * tyz - td(2, 0) / dx) * std::cos(m.theta_zx_rad);
  m.theta_zy_rad = std::atan(tzy);
  const double dz = td(2, 2) * std::cos(m.theta_zx_rad) * std::cos(m.theta_zy_rad);
  m.scale_factor_error =
      Eigen::Vector3d(1.0 / dx, 1.0 / dy, 1.0 / dz) - Eigen::Vector3d::Ones();
  m.bias_mps2 = offset * mps2_per_unit;
  return m;
}

void CheckInvertible(const Eigen::Matrix3d& m, const std::string& where) {
  if (!m.allFinite()) {
    throw Error(ErrorKind::kInput,
                fmt::format("{}: not a matrix of finite numbers", where));
  }
  const Eigen::Vector3d s = Eigen::JacobiSVD<Eigen::Matrix3d>(m).singularValues();
  if (!(s[2] > 0.0) || s[0] / s[2] > 1e8) {
    throw Error(ErrorKind::kInput,
                fmt::format("{}: the matrix is singular (singular values {:.4g}, {:.4g}, "
                            "{:.4g}); it cannot be a calibration",
                            where,
                            s[0],
                            s[1],
                            s[2]));
  }
}

void CheckRotation(const Eigen::Matrix3d& r, const std::string& where) {
  const double off =
      (r.transpose() * r - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
  const double det = r.allFinite() ? r.determinant() : 0.0;
  if (!r.allFinite() || off > 1e-6 || std::abs(det - 1.0) > 1e-6) {
    throw Error(
        ErrorKind::kInput,
        fmt::format("{}: not a rotation (RᵀR differs from the identity by {:.3g}, "
                    "det {:.6g}); it must be orthonormal with det 1",
                    where,
                    off,
                    det));
  }
}

void CheckTriangular(const Eigen::Matrix3d& m, bool lower, const std::string& where) {
  const double scale = m.cwiseAbs().maxCoeff();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      const bool outside = lower ? j > i : j < i;
      if (outside && std::abs(m(i, j)) > 1e-12 * scale) {
        throw Error(ErrorKind::kInput,
                    fmt::format("{}: entry ({}, {}) = {:.6g} but the matrix must be {} "
                                "triangular",
                                where,
                                i + 1,
                                j + 1,
                                m(i, j),
                                lower ? "lower" : "upper"));
      }
    }
  }
}

}  // namespace mpcal::export_formats
