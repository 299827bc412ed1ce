#include "mpcal/gravity.h"

#include <cmath>

#include <fmt/format.h>
#include <GeographicLib/NormalGravity.hpp>

#include "mpcal/error.h"

namespace mpcal {

double NormalGravityMps2(double latitude_deg, double height_m) {
  if (!std::isfinite(latitude_deg) || std::abs(latitude_deg) > 90.0) {
    throw Error(ErrorKind::kOption,
                fmt::format("latitude {} deg is outside -90..90; give the geodetic "
                            "latitude in degrees",
                            latitude_deg),
                Advice{{{Option::kLatitude, ""}}, Stage::kNone, ""});
  }
  // Normal gravity is defined near the ellipsoid; beyond ±100 km a height is
  // almost surely a unit mistake (mm, feet) rather than a real site.
  if (!std::isfinite(height_m) || std::abs(height_m) > 100e3) {
    throw Error(ErrorKind::kOption,
                fmt::format("height {} m is outside -100..100 km; give the ellipsoidal "
                            "height in metres",
                            height_m),
                Advice{{{Option::kHeight, ""}}, Stage::kNone, ""});
  }
  double gamma_north_mps2 = 0.0;
  double gamma_up_mps2 = 0.0;
  GeographicLib::NormalGravity::WGS84().Gravity(
      latitude_deg, height_m, gamma_north_mps2, gamma_up_mps2);
  return std::hypot(gamma_north_mps2, gamma_up_mps2);
}

}  // namespace mpcal
