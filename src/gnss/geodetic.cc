// Geodetic coordinates to and from a local east-north-up frame (WGS84).
#include <GeographicLib/LocalCartesian.hpp>

#include "mpcal/gnss.h"

namespace mpcal {

Eigen::Vector3d GeodeticToEnu(const Geodetic& origin, const Geodetic& point) {
  const GeographicLib::LocalCartesian local(
      origin.latitude_deg, origin.longitude_deg, origin.height_m);
  Eigen::Vector3d enu;
  local.Forward(
      point.latitude_deg, point.longitude_deg, point.height_m, enu.x(), enu.y(), enu.z());
  return enu;
}

Geodetic EnuToGeodetic(const Geodetic& origin, const Eigen::Vector3d& enu_m) {
  const GeographicLib::LocalCartesian local(
      origin.latitude_deg, origin.longitude_deg, origin.height_m);
  Geodetic g;
  local.Reverse(
      enu_m.x(), enu_m.y(), enu_m.z(), g.latitude_deg, g.longitude_deg, g.height_m);
  return g;
}

}  // namespace mpcal
