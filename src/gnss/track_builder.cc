// Collecting the epochs of a reference track: time order, duplicates, the
// quality filter, and positions turned into east-north-up about the first.
#include <GeographicLib/Geocentric.hpp>

#include "gnss/gnss_fields.h"
#include "mpcal/error.h"

namespace mpcal::gnss_internal {

TrackBuilder::TrackBuilder(const std::string& origin, const GnssReadOptions& options)
    : origin_(origin), options_(options) {
  track_.source = origin;
}

bool TrackBuilder::KeepQuality(int quality, bool rtklib_order) {
  if (rtklib_order && options_.max_rtklib_quality > 0 &&
      quality > options_.max_rtklib_quality) {
    ++dropped_quality_;
    return false;
  }
  return true;
}

void TrackBuilder::AddGeodetic(double time_s,
                               const Geodetic& g,
                               int quality,
                               const Where& where) {
  if (!CheckTime(time_s, where)) return;
  if (!local_) {
    local_.emplace(g.latitude_deg, g.longitude_deg, g.height_m);
    track_.origin = g;
  }
  Eigen::Vector3d enu;
  local_->Forward(g.latitude_deg, g.longitude_deg, g.height_m, enu.x(), enu.y(), enu.z());
  Push(time_s, enu, quality);
}

void TrackBuilder::AddEcef(double time_s,
                           const Eigen::Vector3d& xyz,
                           int quality,
                           const Where& where) {
  if (xyz.norm() < 6.0e6 || xyz.norm() > 7.0e6) {
    throw Error(ErrorKind::kInput,
                fmt::format("{}: ECEF position ({:.3f}, {:.3f}, {:.3f}) m is not near "
                            "the Earth's surface "
                            "({:.0f} m from its centre)",
                            where.Prefix(),
                            xyz.x(),
                            xyz.y(),
                            xyz.z(),
                            xyz.norm()));
  }
  Geodetic g;
  GeographicLib::Geocentric::WGS84().Reverse(
      xyz.x(), xyz.y(), xyz.z(), g.latitude_deg, g.longitude_deg, g.height_m);
  AddGeodetic(time_s, g, quality, where);
}

void TrackBuilder::AddLocal(double time_s,
                            const Eigen::Vector3d& enu,
                            int quality,
                            const Where& where,
                            bool relative) {
  if (!CheckTime(time_s, where)) return;
  if (relative && !first_local_) first_local_ = enu;
  Push(time_s, relative ? Eigen::Vector3d(enu - *first_local_) : enu, quality);
}

GnssTrack TrackBuilder::Finish(std::string_view what) {
  if (dropped_quality_ > 0) {
    track_.warnings.push_back(
        fmt::format("{}: dropped {} epochs with quality worse than Q={}",
                    origin_,
                    dropped_quality_,
                    options_.max_rtklib_quality));
  }
  if (duplicates_ > 0) {
    track_.warnings.push_back(
        fmt::format("{}: dropped {} epochs with a repeated time", origin_, duplicates_));
  }
  if (track_.empty()) {
    throw Error(
        ErrorKind::kInput,
        fmt::format("{}: no {} epochs{}",
                    origin_,
                    what,
                    dropped_quality_ > 0 ? " left after the quality filter" : ""));
  }
  return std::move(track_);
}

bool TrackBuilder::CheckTime(double time_s, const Where& where) {
  if (track_.empty()) return true;
  const double last = track_.time_s.back();
  if (time_s == last) {
    ++duplicates_;
    return false;
  }
  if (time_s < last) {
    throw Error(ErrorKind::kTime,
                fmt::format("{}: time goes back by {:.3f} s (from the previous epoch); "
                            "a reference track must be in time order",
                            where.Prefix(),
                            last - time_s));
  }
  return true;
}

void TrackBuilder::Push(double time_s, const Eigen::Vector3d& enu, int quality) {
  track_.time_s.push_back(time_s);
  track_.enu_m.push_back(enu);
  track_.quality.push_back(quality);
}

}  // namespace mpcal::gnss_internal
