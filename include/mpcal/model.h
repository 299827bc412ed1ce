/// \file model.h
/// \brief The 9-parameter accelerometer error model of Shin & El-Sheimy (2001)
/// as written by Souza & Machado (2016), eqs 8-10, and its 6-parameter subset.
///
/// A raw reading `Y` (m/s², already scaled by the nominal sensitivity) of a
/// triad with bias `b`, scale-factor errors `s` (an ideal axis has `s = 0`) and
/// non-orthogonality angles `θyz, θzx, θzy` (radians) is corrected to the
/// specific force `a` in an orthogonal frame by
///
///     a = T · diag(1/(1+s)) · (Y − b)                         (Correct)
///     Y = b + diag(1+s) · T⁻¹ · a                             (Forward)
///
/// with the lower-triangular
///
///     T = [ 1                                    0                  0
///           tan θyz                              1/cos θyz          0
///           tan θzx tan θyz − tan θzy / cos θzx  tan θzx / cos θyz  1/(cos θzx cos θzy)
///           ]
///
/// Frame: x along the sensor's x axis, y in the plane of the sensor's x and y
/// axes, z completing a right-handed orthogonal triad. These three constraints
/// are why the model has 9 parameters rather than the 12 of a general affine
/// model: gravity alone cannot observe a rotation of the whole triad.
///
/// The type is templated on the scalar so that Ceres' automatic
/// differentiation (ceres::Jet) runs through exactly the code users call.
#pragma once

#include <array>
#include <cmath>
#include <optional>
#include <string_view>

#include <Eigen/Core>

namespace mpcal {

/// Which parameters are estimated.
enum class ModelKind {
  /// All 9: bias, scale-factor error, non-orthogonality (the paper's model).
  kShinElSheimy9,
  /// Bias and scale-factor error only; the angles are held at zero. The
  /// classical six-position calibration (ArduPilot, PX4).
  kBiasScale6,
};

/// "shin-el-sheimy-9" or "bias-scale-6".
std::string_view ToString(ModelKind kind);
/// Inverse of ToString; std::nullopt for an unknown name.
std::optional<ModelKind> ParseModelKind(std::string_view name);
/// Number of estimated parameters: 9 or 6.
int ParameterCount(ModelKind kind);

/// Number of entries in the packed parameter vector (always all 9).
inline constexpr int kNumModelParameters = 9;

/// Packed order of the parameters: bias x, y, z (m/s²), scale-factor error
/// x, y, z (dimensionless), θyz, θzx, θzy (rad). Names carry their unit.
inline constexpr std::array<std::string_view, kNumModelParameters> kParameterNames = {
    "bias_x_mps2",
    "bias_y_mps2",
    "bias_z_mps2",
    "scale_factor_error_x",
    "scale_factor_error_y",
    "scale_factor_error_z",
    "theta_yz_rad",
    "theta_zx_rad",
    "theta_zy_rad"};

/// The error model. All members zero is an ideal sensor.
template <typename Scalar>
struct ErrorModelT {
  using Vector3 = Eigen::Matrix<Scalar, 3, 1>;
  using Matrix3 = Eigen::Matrix<Scalar, 3, 3>;

  Vector3 bias_mps2 = Vector3::Zero();
  /// Scale-factor error s: the axis reads (1 + s) times the true value.
  Vector3 scale_factor_error = Vector3::Zero();
  Scalar theta_yz_rad = Scalar(0);
  Scalar theta_zx_rad = Scalar(0);
  Scalar theta_zy_rad = Scalar(0);

  /// The non-orthogonality matrix T above.
  Matrix3 NonOrthogonality() const {
    using std::cos;
    using std::tan;
    const Scalar cyz = cos(theta_yz_rad);
    const Scalar czx = cos(theta_zx_rad);
    const Scalar czy = cos(theta_zy_rad);
    const Scalar tyz = tan(theta_yz_rad);
    const Scalar tzx = tan(theta_zx_rad);
    const Scalar tzy = tan(theta_zy_rad);
    Matrix3 t = Matrix3::Zero();
    t(0, 0) = Scalar(1);
    t(1, 0) = tyz;
    t(1, 1) = Scalar(1) / cyz;
    t(2, 0) = tzx * tyz - tzy / czx;
    t(2, 1) = tzx / cyz;
    t(2, 2) = Scalar(1) / (czx * czy);
    return t;
  }

  /// Specific force (m/s², orthogonal frame) from a reading (m/s²): eqs 8-10.
  Vector3 Correct(const Vector3& reading_mps2) const {
    using std::cos;
    using std::tan;
    const Vector3 d = reading_mps2 - bias_mps2;
    Vector3 a;
    a.x() = d.x() / (Scalar(1) + scale_factor_error.x());
    a.y() = a.x() * tan(theta_yz_rad) +
            d.y() / ((Scalar(1) + scale_factor_error.y()) * cos(theta_yz_rad));
    a.z() = -a.x() * tan(theta_zy_rad) / cos(theta_zx_rad) + a.y() * tan(theta_zx_rad) +
            d.z() / ((Scalar(1) + scale_factor_error.z()) * cos(theta_zx_rad) *
                     cos(theta_zy_rad));
    return a;
  }

  /// The reading (m/s²) a sensor with these errors gives for the specific
  /// force `a` (m/s²): the exact inverse of Correct.
  Vector3 Forward(const Vector3& specific_force_mps2) const {
    const Matrix3 t = NonOrthogonality();
    // T is lower triangular: forward substitution, exact for any scalar type.
    Vector3 w;
    w.x() = specific_force_mps2.x() / t(0, 0);
    w.y() = (specific_force_mps2.y() - t(1, 0) * w.x()) / t(1, 1);
    w.z() = (specific_force_mps2.z() - t(2, 0) * w.x() - t(2, 1) * w.y()) / t(2, 2);
    return bias_mps2 + (Vector3::Ones() + scale_factor_error).cwiseProduct(w);
  }

  /// Packs into `p[0..8]` in the order of kParameterNames.
  void ToParameters(Scalar* p) const {
    for (int i = 0; i < 3; ++i) {
      p[i] = bias_mps2[i];
      p[3 + i] = scale_factor_error[i];
    }
    p[6] = theta_yz_rad;
    p[7] = theta_zx_rad;
    p[8] = theta_zy_rad;
  }

  /// Unpacks from `p[0..8]` in the order of kParameterNames.
  static ErrorModelT FromParameters(const Scalar* p) {
    ErrorModelT m;
    for (int i = 0; i < 3; ++i) {
      m.bias_mps2[i] = p[i];
      m.scale_factor_error[i] = p[3 + i];
    }
    m.theta_yz_rad = p[6];
    m.theta_zx_rad = p[7];
    m.theta_zy_rad = p[8];
    return m;
  }

  /// The same model in another scalar type (e.g. double -> ceres::Jet).
  template <typename Other>
  ErrorModelT<Other> cast() const {
    ErrorModelT<Other> m;
    m.bias_mps2 = bias_mps2.template cast<Other>();
    m.scale_factor_error = scale_factor_error.template cast<Other>();
    m.theta_yz_rad = Other(theta_yz_rad);
    m.theta_zx_rad = Other(theta_zx_rad);
    m.theta_zy_rad = Other(theta_zy_rad);
    return m;
  }
};

using ErrorModel = ErrorModelT<double>;

/// Packed parameters as an Eigen vector (order of kParameterNames).
Eigen::Matrix<double, kNumModelParameters, 1> ToVector(const ErrorModel& m);
/// Inverse of ToVector.
ErrorModel FromVector(const Eigen::Matrix<double, kNumModelParameters, 1>& v);

}  // namespace mpcal
