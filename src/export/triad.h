// The calibration as the matrices other tools write, and back: the
// accelerometer's affine correction, the matrix decompositions that move
// between mpcal's lower-triangular frame and the tools' (rotation times
// triangular), and the checks a tool's matrix must pass.
#pragma once

#include <string>

#include <Eigen/Core>

#include "mpcal/calibration.h"

namespace mpcal::export_formats {

/// m = rotation · triangular, the triangular factor with a positive
/// diagonal (unique for an invertible m).
struct Factored {
  Eigen::Matrix3d rotation;
  Eigen::Matrix3d triangular;
};
/// m = R·U, U upper triangular (QR).
Factored RotationTimesUpper(const Eigen::Matrix3d& m);
/// m = R·L, L lower triangular (QL).
Factored RotationTimesLower(const Eigen::Matrix3d& m);
/// m = L·R, L lower triangular: returned as {R, L}.
Factored LowerTimesRotation(const Eigen::Matrix3d& m);

/// The rotation's angle (rad).
double RotationAngle(const Eigen::Matrix3d& r);

/// The accelerometer's correction as a = linear·(reading − offset) in the
/// readings' units: linear = T·diag(1/(1+s))·mps2_per_unit, offset =
/// bias/mps2_per_unit.
struct AccelAffine {
  Eigen::Matrix3d linear;
  Eigen::Vector3d offset;
};
AccelAffine AccelOf(const Calibration& c);

/// The 9-parameter model and nominal factor for a lower-triangular `linear`
/// with a positive diagonal, `offset` in the readings' units: the inverse
/// of AccelOf. `mps2_per_unit` is the nominal factor to use.
ErrorModel ModelOfLower(const Eigen::Matrix3d& linear,
                        const Eigen::Vector3d& offset,
                        double mps2_per_unit);

/// Throws mpcal::Error naming `where` when m is not finite or not
/// invertible (its condition number above 1e8).
void CheckInvertible(const Eigen::Matrix3d& m, const std::string& where);
/// Throws mpcal::Error naming `where` when r is not a rotation (RᵀR = I and
/// det R = 1 to 1e-6).
void CheckRotation(const Eigen::Matrix3d& r, const std::string& where);
/// Throws mpcal::Error naming `where` when m has an entry above the
/// diagonal (lower) or below it (upper) larger than 1e-12·|m|.
void CheckTriangular(const Eigen::Matrix3d& m, bool lower, const std::string& where);

}  // namespace mpcal::export_formats
