/// \file sphere_fit.h
/// \brief The sphere that static mean readings lie on: its centre is the
/// offset of the readings (raw counts sit near 32768, a consumer part has a
/// bias of up to 0.3 g) and its radius one g in the readings' units, the
/// nominal scale of raw counts.
///
/// The centre is fitted without any knowledge of the units by linear least
/// squares, |m_k|² = 2 m_k·c + d (Eigen's column-pivoting QR). The fit needs
/// at least 4 means that spread over the sphere; otherwise the centre is 0
/// for readings in g or m/s², and for counts the power of two nearest the
/// median reading (an unsigned ADC's mid-scale) or 0 when readings are
/// negative. Scale errors of a few per cent change the directions by well
/// under a degree, so a sphere (not an ellipsoid) is all the nominal scale
/// and the directions need.
#pragma once

#include <span>

#include <Eigen/Core>

#include "mpcal/units.h"

namespace mpcal {

/// Offset and radius that turn mean readings into unit directions.
struct SphereFit {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();  ///< recording units
  double radius = 0.0;  ///< recording units (≈ g in those units)
  /// True when the centre came from the least-squares fit, false when from
  /// the fallback described in the file comment.
  bool fitted = false;
  /// RMS of |m_k − c| − radius over the means (recording units).
  double residual_rms = 0.0;
};

/// Fits the offset of `means` (any units) as the file comment describes.
/// Never throws; with no means the centre is 0 and the radius 0.
SphereFit FitSphere(std::span<const Eigen::Vector3d> means, AccelUnits units);

}  // namespace mpcal
