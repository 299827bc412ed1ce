/// \file gnss.h
/// \brief GNSS reference tracks for field verification (docs/method.md §5): readers
/// for RTKLIB .pos files, NMEA GGA sentences and plain CSV, the conversion of
/// geodetic positions to a local east-north-up frame at the first fix, and the
/// writer of RTKLIB .pos files that `mpcal simulate walk` uses.
///
/// Time: `time_s` of a track is seconds since 1970-01-01 00:00:00 *on the
/// file's own time scale*, read from its calendar date and time of day without
/// any leap-second conversion (the way IMU loggers stamp "unix time" from a
/// receiver). A file in GPST is therefore 18 s (the leap seconds since 1980,
/// as of 2017) ahead of the same instant in UTC; `time_system` says which.
///
/// Frame: `enu_m` is east, north, up (metres) in the local tangent frame of the
/// WGS84 ellipsoid at the first fix (GeographicLib::LocalCartesian); for a
/// CSV already in e, n, u the values are kept as they are.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

namespace mpcal {

/// The time scale of a reference file's timestamps.
enum class TimeSystem {
  kGpst,     ///< GPS time (RTKLIB's default)
  kUtc,      ///< UTC (NMEA; RTKLIB with "UTC" in the header)
  kUnknown,  ///< a CSV: whatever clock the user wrote
};
/// "gpst", "utc" or "unknown".
std::string_view ToString(TimeSystem system);

/// The format of a reference file.
enum class GnssFormat { kAuto, kRtklibPos, kNmea, kCsv };
/// "auto", "pos", "nmea" or "csv".
std::string_view ToString(GnssFormat format);
/// Inverse of ToString (also "rtklib"); nullopt if unknown.
std::optional<GnssFormat> ParseGnssFormat(std::string_view name);

/// A point on the WGS84 ellipsoid.
struct Geodetic {
  double latitude_deg = 0.0;
  double longitude_deg = 0.0;
  double height_m = 0.0;  ///< above the ellipsoid
};

/// A reference trajectory, time-ordered.
struct GnssTrack {
  /// Seconds since 1970-01-01 on `time_system` (see the file comment).
  std::vector<double> time_s;
  /// East, north, up (m) from `origin`.
  std::vector<Eigen::Vector3d> enu_m;
  /// Solution quality per epoch as the file gives it: RTKLIB Q (1 fix,
  /// 2 float, 3 SBAS, 4 DGPS, 5 single, 6 PPP), NMEA GGA fix quality (1 GPS,
  /// 2 DGPS, 4 RTK fixed, 5 RTK float, ...); 0 when the file has none.
  std::vector<int> quality;
  /// The first fix, origin of `enu_m`; nullopt for a CSV in e, n, u.
  std::optional<Geodetic> origin;
  TimeSystem time_system = TimeSystem::kUnknown;
  /// Path, or "<simulated>", for messages.
  std::string source;
  /// Non-fatal findings (skipped sentences, dropped epochs).
  std::vector<std::string> warnings;

  std::size_t size() const { return time_s.size(); }
  bool empty() const { return time_s.empty(); }
};

struct GnssReadOptions {
  /// The file's format; kAuto looks at the content ('$' sentences: NMEA;
  /// '%' header with GPST/UTC: RTKLIB; a header with t and lat/e: CSV).
  GnssFormat format = GnssFormat::kAuto;
  /// Epochs whose quality is worse than this are dropped with a warning: a
  /// larger RTKLIB Q is a worse solution (1 fix ... 5 single). 0 keeps every
  /// epoch. For NMEA the GGA fix quality is not ordered that way, so only
  /// quality 0 (no fix) is dropped whatever this says.
  int max_rtklib_quality = 0;

  /// "" when valid, otherwise names the first bad field.
  std::string Validate() const;
};

/// Reads a reference track from a file.
/// \throws mpcal::Error for a missing, unreadable or empty file, a format
///   that cannot be recognised, a malformed line (the message gives the file,
///   the line number and the field), a non-finite or out-of-range value
///   (latitude outside ±90°, a date that does not exist), time going back, or
///   no epoch left.
GnssTrack ReadGnss(const std::string& path, const GnssReadOptions& options = {});

/// Parses the text of a reference file; `origin` names it in messages.
/// \throws mpcal::Error as ReadGnss.
GnssTrack ParseGnss(const std::string& text,
                    const std::string& origin,
                    const GnssReadOptions& options = {});

/// East, north, up (m) of `point` in the tangent frame at `origin`.
Eigen::Vector3d GeodeticToEnu(const Geodetic& origin, const Geodetic& point);
/// Inverse of GeodeticToEnu.
Geodetic EnuToGeodetic(const Geodetic& origin, const Eigen::Vector3d& enu_m);

/// One epoch of an RTKLIB .pos file to write.
struct PosEpoch {
  double time_s = 0.0;  ///< seconds since 1970-01-01 on the file's time scale
  Geodetic position;
  int quality = 1;
  int satellites = 0;
  /// 1σ north, east, up (m) as RTKLIB writes them (sdn, sde, sdu).
  Eigen::Vector3d std_neu_m = Eigen::Vector3d::Zero();
};

/// The text of an RTKLIB .pos file (lat/lon/height in degrees, calendar time
/// with millisecond resolution, header in the layout RTKLIB's rnx2rtkp
/// writes) that ParseGnss reads back.
/// \param time_system kGpst or kUtc (kUnknown is written as GPST).
/// \param program written on the header's "% program" line.
std::string FormatRtklibPos(const std::vector<PosEpoch>& epochs,
                            TimeSystem time_system = TimeSystem::kGpst,
                            std::string_view program = "mpcal");

}  // namespace mpcal
