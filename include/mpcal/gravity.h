/// \file gravity.h
/// \brief The magnitude of gravity, the only reference of the multi-position
/// method. A wrong value shows up one-for-one as a common scale-factor error,
/// so use the local value when you know it.
#pragma once

#include "mpcal/units.h"

namespace mpcal {

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
