// What the GNSS readers share (room-private): where a value came from, the
// number, integer, angle and calendar fields of the three formats, and the
// builder that collects epochs in time order and turns positions into
// east-north-up.
#pragma once

#include <optional>
#include <string>
#include <string_view>

#include <fmt/format.h>
#include <Eigen/Core>
#include <GeographicLib/LocalCartesian.hpp>

#include "mpcal/gnss.h"

namespace mpcal::gnss_internal {

// GPS time started at 1980-01-06 00:00:00, 315964800 s after the Unix epoch
// on a clock without leap seconds.
inline constexpr double kGpsEpochS = 315964800.0;
inline constexpr double kSecondsPerWeek = 604800.0;
inline constexpr double kSecondsPerDay = 86400.0;

// Where a value came from, for messages: "file:line: field 'name'".
struct Where {
  const std::string& origin;
  std::size_t line;
  std::string Prefix() const { return fmt::format("{}:{}", origin, line); }
};

/// A finite number (a leading '+' allowed).
/// \throws mpcal::Error naming `where` and `field` otherwise.
double ParseNumber(std::string_view token, const Where& where, std::string_view field);
/// An integer of at most 1e9 in magnitude, written as a number.
int ParseInt(std::string_view token, const Where& where, std::string_view field);
/// \throws mpcal::Error for a latitude beyond ±90° or a longitude beyond ±360°.
void CheckLatLon(double lat_deg, double lon_deg, const Where& where);
/// Seconds since 1970-01-01 of a calendar date and time on one clock.
double CalendarSeconds(
    int year, int month, int day, double seconds_of_day, const Where& where);
/// "2025/08/28" "17:30:39.749" (RTKLIB also writes '-' in dates).
double ParseCalendar(std::string_view date, std::string_view time, const Where& where);

// Collects epochs, checks time order, and turns positions into ENU.
class TrackBuilder {
 public:
  TrackBuilder(const std::string& origin, const GnssReadOptions& options);

  // Quality filter per RTKLIB convention; false when dropped.
  bool KeepQuality(int quality, bool rtklib_order);
  void AddGeodetic(double time_s, const Geodetic& g, int quality, const Where& where);
  void AddEcef(double time_s,
               const Eigen::Vector3d& xyz,
               int quality,
               const Where& where);
  // Positions already local (e, n, u): kept relative to the first one when
  // `relative`, as they are otherwise.
  void AddLocal(double time_s,
                const Eigen::Vector3d& enu,
                int quality,
                const Where& where,
                bool relative);
  // The track, with warnings for what was dropped.
  // \throws mpcal::Error when no epoch is left; `what` names the epochs.
  GnssTrack Finish(std::string_view what);

  GnssTrack& track() { return track_; }

 private:
  bool CheckTime(double time_s, const Where& where);
  void Push(double time_s, const Eigen::Vector3d& enu, int quality);

  const std::string& origin_;
  GnssReadOptions options_;
  GnssTrack track_;
  std::optional<GeographicLib::LocalCartesian> local_;
  std::optional<Eigen::Vector3d> first_local_;
  int dropped_quality_ = 0;
  int duplicates_ = 0;
};

// The three readers (rtklib_pos.cc, nmea.cc, gnss_csv.cc).
GnssTrack ParseRtklibPos(const std::string& text,
                         const std::string& origin,
                         const GnssReadOptions& options);
GnssTrack ParseNmea(const std::string& text,
                    const std::string& origin,
                    const GnssReadOptions& options);
GnssTrack ParseGnssCsv(const std::string& text,
                       const std::string& origin,
                       const GnssReadOptions& options);

}  // namespace mpcal::gnss_internal
