/// \file gravity.h
/// \brief The magnitude of gravity, the only reference of the multi-position
/// method. A wrong value shows up one-for-one as a common scale-factor error,
/// so use the local value when you know it.
#pragma once

#include "mpcal/units.h"

namespace mpcal {

/// The plausible range of gravity's magnitude (m/s²), the one range every
/// check uses (options, calibration files, simulators). Normal gravity runs
/// from 9.7803 at the equator to 9.8322 at the poles at sea level; a site
/// 9 km up is 0.03 m/s² lower, and local anomalies are below 0.003 m/s².
/// The bounds leave a margin of about 0.07 m/s² beyond both, and stay tight
/// enough that a value in another unit (32.2 ft/s², 1 g, 980 Gal) or a typo
/// (9.08, 98.1) is refused rather than made into a scale error of up to 10 %.
inline constexpr double kMinGravityMps2 = 9.7;
inline constexpr double kMaxGravityMps2 = 9.9;
inline bool IsPlausibleGravity(double g_mps2) {
  return g_mps2 >= kMinGravityMps2 && g_mps2 <= kMaxGravityMps2;
}

/// Normal gravity of the WGS84 ellipsoid (m/s²) at geodetic latitude
/// `latitude_deg` (degrees, −90..90) and height `height_m` above the
/// ellipsoid (metres), by GeographicLib::NormalGravity (Somigliana's formula
/// and its exact height dependence). Ranges from 9.7803 at the equator to
/// 9.8322 at the poles at zero height.
///
/// \throws mpcal::Error if the latitude is outside [−90, 90] or either
///   argument is not finite, or the height is outside ±100 km.
double NormalGravityMps2(double latitude_deg, double height_m = 0.0);

}  // namespace mpcal
