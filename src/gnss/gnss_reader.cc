// Readers of GNSS reference tracks: RTKLIB .pos, NMEA GGA, CSV.
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <charconv>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include <fast_float/fast_float.h>
#include <fmt/format.h>
#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/LocalCartesian.hpp>

#include "mpcal/error.h"
#include "mpcal/gnss.h"
#include "mpcal/text_input.h"

namespace mpcal {
namespace {

// GPS time started at 1980-01-06 00:00:00, 315964800 s after the Unix epoch
// on a clock without leap seconds.
constexpr double kGpsEpochS = 315964800.0;
constexpr double kSecondsPerWeek = 604800.0;
constexpr double kSecondsPerDay = 86400.0;

std::string Lower(std::string_view s) {
  std::string out(s);
  std::transform(out.begin(), out.end(), out.begin(), [](unsigned char c) {
    return static_cast<char>(std::tolower(c));
  });
  return out;
}

std::string_view Trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front())))
    s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back())))
    s.remove_suffix(1);
  return s;
}

std::vector<std::string_view> SplitWhitespace(std::string_view line) {
  std::vector<std::string_view> tokens;
  std::size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    const std::size_t start = i;
    while (i < line.size() && !std::isspace(static_cast<unsigned char>(line[i]))) ++i;
    if (i > start) tokens.push_back(line.substr(start, i - start));
  }
  return tokens;
}

std::vector<std::string_view> SplitOn(std::string_view line, char delimiter) {
  std::vector<std::string_view> fields;
  std::size_t start = 0;
  while (true) {
    const std::size_t pos = line.find(delimiter, start);
    if (pos == std::string_view::npos) {
      fields.push_back(Trim(line.substr(start)));
      return fields;
    }
    fields.push_back(Trim(line.substr(start, pos - start)));
    start = pos + 1;
  }
}

// Splits text into lines (LF or CRLF), keeping 1-based line numbers.
std::vector<std::string_view> Lines(const std::string& text) {
  std::vector<std::string_view> lines;
  std::string_view rest(text);
  while (!rest.empty()) {
    const std::size_t pos = rest.find('\n');
    std::string_view line = rest.substr(0, pos);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    lines.push_back(line);
    if (pos == std::string_view::npos) break;
    rest.remove_prefix(pos + 1);
  }
  return lines;
}

// Where a value came from, for messages: "file:line: field 'name'".
struct Where {
  const std::string& origin;
  std::size_t line;
  std::string Prefix() const { return fmt::format("{}:{}", origin, line); }
};

double ParseNumber(std::string_view token, const Where& where, std::string_view field) {
  double value = 0.0;
  const char* first = token.data();
  const char* last = token.data() + token.size();
  if (first != last && *first == '+') ++first;
  const auto result = fast_float::from_chars(first, last, value);
  if (token.empty() || result.ec != std::errc() || result.ptr != last) {
    throw Error(
        fmt::format("{}: {} is '{}', not a number", where.Prefix(), field, token));
  }
  if (!std::isfinite(value)) {
    throw Error(
        fmt::format("{}: {} is '{}', not a finite number", where.Prefix(), field, token));
  }
  return value;
}

int ParseInt(std::string_view token, const Where& where, std::string_view field) {
  const double v = ParseNumber(token, where, field);
  if (v != std::floor(v) || std::abs(v) > 1e9) {
    throw Error(
        fmt::format("{}: {} is '{}', not an integer", where.Prefix(), field, token));
  }
  return static_cast<int>(v);
}

void CheckLatLon(double lat_deg, double lon_deg, const Where& where) {
  if (std::abs(lat_deg) > 90.0) {
    throw Error(
        fmt::format("{}: latitude {} deg is outside -90..90", where.Prefix(), lat_deg));
  }
  if (std::abs(lon_deg) > 360.0) {
    throw Error(fmt::format(
        "{}: longitude {} deg is outside -360..360", where.Prefix(), lon_deg));
  }
}

// Seconds since 1970-01-01 of a calendar date and time on one clock.
double CalendarSeconds(
    int year, int month, int day, double seconds_of_day, const Where& where) {
  using namespace std::chrono;
  const year_month_day ymd{std::chrono::year{year},
                           std::chrono::month{static_cast<unsigned>(month)},
                           std::chrono::day{static_cast<unsigned>(day)}};
  if (!ymd.ok() || year < 1970 || year > 2200) {
    throw Error(fmt::format("{}: date {:04d}/{:02d}/{:02d} does not exist",
                            where.Prefix(),
                            year,
                            month,
                            day));
  }
  const double days = static_cast<double>(sys_days{ymd}.time_since_epoch().count());
  return days * kSecondsPerDay + seconds_of_day;
}

// "2025/08/28" "17:30:39.749" (RTKLIB also writes '-' in dates).
double ParseCalendar(std::string_view date, std::string_view time, const Where& where) {
  const auto fail = [&] {
    return Error(fmt::format(
        "{}: time '{} {}' is not YYYY/MM/DD hh:mm:ss.sss", where.Prefix(), date, time));
  };
  std::string d(date);
  std::replace(d.begin(), d.end(), '-', '/');
  const auto ymd = SplitOn(d, '/');
  const auto hms = SplitOn(time, ':');
  if (ymd.size() != 3 || hms.size() != 3) throw fail();
  int y = 0, mo = 0, da = 0, h = 0, mi = 0;
  double s = 0.0;
  try {
    y = ParseInt(ymd[0], where, "year");
    mo = ParseInt(ymd[1], where, "month");
    da = ParseInt(ymd[2], where, "day");
    h = ParseInt(hms[0], where, "hour");
    mi = ParseInt(hms[1], where, "minute");
    s = ParseNumber(hms[2], where, "seconds");
  } catch (const Error&) {
    throw fail();
  }
  if (mo < 1 || mo > 12 || da < 1 || da > 31 || h < 0 || h > 23 || mi < 0 || mi > 59 ||
      s < 0.0 || s >= 61.0) {
    throw fail();
  }
  return CalendarSeconds(y, mo, da, h * 3600.0 + mi * 60.0 + s, where);
}

// Collects epochs, checks time order, and turns positions into ENU.
class TrackBuilder {
 public:
  TrackBuilder(const std::string& origin, const GnssReadOptions& options)
      : origin_(origin), options_(options) {
    track_.source = origin;
  }

  // Quality filter per RTKLIB convention; false when dropped.
  bool KeepQuality(int quality, bool rtklib_order) {
    if (rtklib_order && options_.max_rtklib_quality > 0 &&
        quality > options_.max_rtklib_quality) {
      ++dropped_quality_;
      return false;
    }
    return true;
  }

  void AddGeodetic(double time_s, const Geodetic& g, int quality, const Where& where) {
    if (!CheckTime(time_s, where)) return;
    if (!local_) {
      local_.emplace(g.latitude_deg, g.longitude_deg, g.height_m);
      track_.origin = g;
    }
    Eigen::Vector3d enu;
    local_->Forward(
        g.latitude_deg, g.longitude_deg, g.height_m, enu.x(), enu.y(), enu.z());
    Push(time_s, enu, quality);
  }

  void AddEcef(double time_s,
               const Eigen::Vector3d& xyz,
               int quality,
               const Where& where) {
    if (xyz.norm() < 6.0e6 || xyz.norm() > 7.0e6) {
      throw Error(fmt::format(
          "{}: ECEF position ({:.3f}, {:.3f}, {:.3f}) m is not near the Earth's surface "
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

  // Positions already local (e, n, u): kept relative to the first one when
  // `relative`, as they are otherwise.
  void AddLocal(double time_s,
                const Eigen::Vector3d& enu,
                int quality,
                const Where& where,
                bool relative) {
    if (!CheckTime(time_s, where)) return;
    if (relative && !first_local_) first_local_ = enu;
    Push(time_s, relative ? Eigen::Vector3d(enu - *first_local_) : enu, quality);
  }

  GnssTrack Finish(std::string_view what) {
    if (dropped_quality_ > 0) {
      track_.warnings.push_back(
          fmt::format("{}: dropped {} epochs with quality worse than Q={}",
                      origin_,
                      dropped_quality_,
                      options_.max_rtklib_quality));
    }
    if (duplicates_ > 0) {
      track_.warnings.push_back(fmt::format(
          "{}: dropped {} epochs with a repeated time", origin_, duplicates_));
    }
    if (track_.empty()) {
      throw Error(
          fmt::format("{}: no {} epochs{}",
                      origin_,
                      what,
                      dropped_quality_ > 0 ? " left after the quality filter" : ""));
    }
    return std::move(track_);
  }

  GnssTrack& track() { return track_; }

 private:
  bool CheckTime(double time_s, const Where& where) {
    if (!track_.empty()) {
      const double last = track_.time_s.back();
      if (time_s == last) {
        ++duplicates_;
        return false;
      }
      if (time_s < last) {
        throw Error(
            fmt::format("{}: time goes back by {:.3f} s (from the previous epoch); "
                        "a reference track must be in time order",
                        where.Prefix(),
                        last - time_s));
      }
    }
    return true;
  }

  void Push(double time_s, const Eigen::Vector3d& enu, int quality) {
    track_.time_s.push_back(time_s);
    track_.enu_m.push_back(enu);
    track_.quality.push_back(quality);
  }

  const std::string& origin_;
  GnssReadOptions options_;
  GnssTrack track_;
  std::optional<GeographicLib::LocalCartesian> local_;
  std::optional<Eigen::Vector3d> first_local_;
  int dropped_quality_ = 0;
  int duplicates_ = 0;
};

// ---------------------------------------------------------------- RTKLIB

enum class PosLayout { kGeodeticDeg, kGeodeticDms, kEcef, kEnu };

// RTKLIB's "dd mm ss.sss": the sign is on the degrees, which may be "-0".
double ParseDms(std::string_view d,
                std::string_view m,
                std::string_view s,
                const Where& where,
                std::string_view field) {
  const double deg = ParseNumber(d, where, field);
  const double min = ParseNumber(m, where, field);
  const double sec = ParseNumber(s, where, field);
  if (min < 0.0 || min >= 60.0 || sec < 0.0 || sec >= 60.0) {
    throw Error(
        fmt::format("{}: {} '{} {} {}' is not degrees, minutes (0-59), seconds (0-60)",
                    where.Prefix(),
                    field,
                    d,
                    m,
                    s));
  }
  const double magnitude = std::abs(deg) + min / 60.0 + sec / 3600.0;
  return d.find('-') != std::string_view::npos ? -magnitude : magnitude;
}

GnssTrack ParseRtklibPos(const std::string& text,
                         const std::string& origin,
                         const GnssReadOptions& options) {
  TrackBuilder builder(origin, options);
  std::optional<PosLayout> layout;
  TimeSystem system = TimeSystem::kGpst;
  double clock_shift_s = 0.0;  // JST is UTC + 9 h
  const auto lines = Lines(text);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const Where where{origin, i + 1};
    const std::string_view line = Trim(lines[i]);
    if (line.empty()) continue;
    if (line.front() == '%') {
      const std::string lower = Lower(line);
      const bool has_time = lower.find("gpst") != std::string::npos ||
                            lower.find("utc") != std::string::npos ||
                            lower.find("jst") != std::string::npos;
      if (!has_time) continue;
      if (lower.find("latitude(d'") != std::string::npos) {
        layout = PosLayout::kGeodeticDms;
      } else if (lower.find("latitude") != std::string::npos) {
        layout = PosLayout::kGeodeticDeg;
      } else if (lower.find("x-ecef") != std::string::npos) {
        layout = PosLayout::kEcef;
      } else if (lower.find("e-baseline") != std::string::npos) {
        layout = PosLayout::kEnu;
      } else {
        continue;  // e.g. "% obs start : 2025/08/28 17:30:39.7 GPST ..."
      }
      if (lower.find("utc") != std::string::npos) {
        system = TimeSystem::kUtc;
      } else if (lower.find("jst") != std::string::npos) {
        system = TimeSystem::kUtc;
        clock_shift_s = -9.0 * 3600.0;
      } else {
        system = TimeSystem::kGpst;
      }
      continue;
    }
    if (!layout) {
      throw Error(fmt::format(
          "{}: data before the column header; an RTKLIB .pos file has a header line "
          "like '%  GPST  latitude(deg) longitude(deg) height(m) Q ns ...' (write the "
          "solution with the header on, out-head=on)",
          where.Prefix()));
    }
    const auto tokens = SplitWhitespace(line);
    // dd mm ss.s dd mm ss.s height, or three numbers.
    const std::size_t position_tokens = *layout == PosLayout::kGeodeticDms ? 7 : 3;
    const std::size_t needed = 2 + position_tokens + 1;  // time, position, Q
    if (tokens.size() < needed) {
      throw Error(fmt::format("{}: {} fields, expected at least {} (time, position, Q)",
                              where.Prefix(),
                              tokens.size(),
                              needed));
    }
    double time_s = 0.0;
    if (tokens[0].find('/') != std::string_view::npos ||
        tokens[0].find('-') != std::string_view::npos) {
      time_s = ParseCalendar(tokens[0], tokens[1], where);
    } else {
      // GPS week and seconds of week (RTKLIB's time format "tow").
      const int week = ParseInt(tokens[0], where, "GPS week");
      const double tow = ParseNumber(tokens[1], where, "time of week");
      if (week < 0 || tow < 0.0 || tow >= kSecondsPerWeek) {
        throw Error(fmt::format("{}: GPS week {} / time of week {} s is out of range",
                                where.Prefix(),
                                tokens[0],
                                tokens[1]));
      }
      time_s = kGpsEpochS + week * kSecondsPerWeek + tow;
    }
    time_s += clock_shift_s;
    const std::size_t q_index = 2 + position_tokens;
    const int quality = ParseInt(tokens[q_index], where, "Q");
    if (!builder.KeepQuality(quality, true)) continue;
    switch (*layout) {
      case PosLayout::kGeodeticDeg: {
        Geodetic g{ParseNumber(tokens[2], where, "latitude"),
                   ParseNumber(tokens[3], where, "longitude"),
                   ParseNumber(tokens[4], where, "height")};
        CheckLatLon(g.latitude_deg, g.longitude_deg, where);
        builder.AddGeodetic(time_s, g, quality, where);
        break;
      }
      case PosLayout::kGeodeticDms: {
        Geodetic g{ParseDms(tokens[2], tokens[3], tokens[4], where, "latitude"),
                   ParseDms(tokens[5], tokens[6], tokens[7], where, "longitude"),
                   ParseNumber(tokens[8], where, "height")};
        CheckLatLon(g.latitude_deg, g.longitude_deg, where);
        builder.AddGeodetic(time_s, g, quality, where);
        break;
      }
      case PosLayout::kEcef:
        builder.AddEcef(time_s,
                        {ParseNumber(tokens[2], where, "x-ecef"),
                         ParseNumber(tokens[3], where, "y-ecef"),
                         ParseNumber(tokens[4], where, "z-ecef")},
                        quality,
                        where);
        break;
      case PosLayout::kEnu:
        builder.AddLocal(time_s,
                         {ParseNumber(tokens[2], where, "e-baseline"),
                          ParseNumber(tokens[3], where, "n-baseline"),
                          ParseNumber(tokens[4], where, "u-baseline")},
                         quality,
                         where,
                         /*relative=*/true);
        break;
    }
  }
  if (!layout) {
    throw Error(fmt::format(
        "{}: no RTKLIB column header (a line like '%  GPST  latitude(deg) longitude(deg) "
        "height(m) Q ...'); is it a .pos file?",
        origin));
  }
  builder.track().time_system = system;
  return builder.Finish("position");
}

// ------------------------------------------------------------------ NMEA

// "ddmm.mmmm" / "dddmm.mmmm" and a hemisphere letter to signed degrees.
double ParseNmeaAngle(std::string_view value,
                      std::string_view hemisphere,
                      int degree_digits,
                      const Where& where,
                      std::string_view field) {
  const auto bad = [&] {
    return Error(fmt::format("{}: {} '{},{}' is not {}mm.mmmm with a hemisphere letter",
                             where.Prefix(),
                             field,
                             value,
                             hemisphere,
                             degree_digits == 2 ? "dd" : "ddd"));
  };
  const std::size_t dot = value.find('.');
  const std::size_t int_digits = dot == std::string_view::npos ? value.size() : dot;
  if (int_digits != static_cast<std::size_t>(degree_digits) + 2) throw bad();
  double deg = 0.0, min = 0.0;
  try {
    deg = ParseNumber(value.substr(0, degree_digits), where, field);
    min = ParseNumber(value.substr(degree_digits), where, field);
  } catch (const Error&) {
    throw bad();
  }
  if (min >= 60.0 || deg < 0.0 || min < 0.0) throw bad();
  const double magnitude = deg + min / 60.0;
  if (hemisphere == "N" || hemisphere == "E") return magnitude;
  if (hemisphere == "S" || hemisphere == "W") return -magnitude;
  throw bad();
}

// "hhmmss.ss" to seconds of the day.
double ParseNmeaTime(std::string_view value, const Where& where) {
  if (value.size() < 6) {
    throw Error(fmt::format("{}: time '{}' is not hhmmss.ss", where.Prefix(), value));
  }
  try {
    const int h = ParseInt(value.substr(0, 2), where, "hour");
    const int m = ParseInt(value.substr(2, 2), where, "minute");
    const double s = ParseNumber(value.substr(4), where, "seconds");
    if (h < 0 || h > 23 || m < 0 || m > 59 || s < 0.0 || s >= 61.0) throw Error("");
    return h * 3600.0 + m * 60.0 + s;
  } catch (const Error&) {
    throw Error(fmt::format("{}: time '{}' is not hhmmss.ss", where.Prefix(), value));
  }
}

// The sentence between '$' and '*' when the checksum matches (or is absent).
std::optional<std::string_view> NmeaBody(std::string_view sentence) {
  const std::size_t star = sentence.rfind('*');
  if (star == std::string_view::npos) return sentence.substr(1);
  const std::string_view body = sentence.substr(1, star - 1);
  const std::string_view sum = Trim(sentence.substr(star + 1));
  unsigned expected = 0;
  const auto r = std::from_chars(sum.data(), sum.data() + sum.size(), expected, 16);
  if (sum.size() != 2 || r.ec != std::errc() || r.ptr != sum.data() + sum.size()) {
    return std::nullopt;
  }
  unsigned actual = 0;
  for (const char c : body) actual ^= static_cast<unsigned char>(c);
  if (actual != expected) return std::nullopt;
  return body;
}

GnssTrack ParseNmea(const std::string& text,
                    const std::string& origin,
                    const GnssReadOptions& options) {
  TrackBuilder builder(origin, options);
  const auto lines = Lines(text);
  // The date comes from RMC (ddmmyy) or ZDA sentences; GGA has only the time
  // of day. Epochs before the first dated sentence take that first date.
  std::optional<double> day_start_s;
  for (std::size_t i = 0; i < lines.size() && !day_start_s; ++i) {
    const std::size_t dollar = lines[i].find('$');
    if (dollar == std::string_view::npos) continue;
    const auto body = NmeaBody(lines[i].substr(dollar));
    if (!body || body->size() < 6) continue;
    const auto f = SplitOn(*body, ',');
    const Where where{origin, i + 1};
    const std::string_view type = f[0].substr(f[0].size() >= 3 ? f[0].size() - 3 : 0);
    if (type == "RMC" && f.size() > 9 && f[9].size() == 6) {
      const int dd = ParseInt(f[9].substr(0, 2), where, "RMC day");
      const int mm = ParseInt(f[9].substr(2, 2), where, "RMC month");
      const int yy = ParseInt(f[9].substr(4, 2), where, "RMC year");
      day_start_s = CalendarSeconds(yy < 80 ? 2000 + yy : 1900 + yy, mm, dd, 0.0, where);
    } else if (type == "ZDA" && f.size() > 4 && !f[2].empty()) {
      day_start_s = CalendarSeconds(ParseInt(f[4], where, "ZDA year"),
                                    ParseInt(f[3], where, "ZDA month"),
                                    ParseInt(f[2], where, "ZDA day"),
                                    0.0,
                                    where);
    }
  }
  if (!day_start_s) {
    builder.track().warnings.push_back(fmt::format(
        "{}: no date (no RMC or ZDA sentence); times are seconds of the day from "
        "1970-01-01, so align with --time-offset or by the start of motion",
        origin));
  }
  double day_offset_s = day_start_s.value_or(0.0);
  double last_time_of_day = -1.0;
  int bad_checksums = 0;
  std::size_t first_bad_line = 0;
  int no_fix = 0;
  int gga = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const Where where{origin, i + 1};
    const std::size_t dollar = lines[i].find('$');
    if (dollar == std::string_view::npos) continue;
    const auto body = NmeaBody(Trim(lines[i].substr(dollar)));
    if (!body) {
      if (bad_checksums++ == 0) first_bad_line = i + 1;
      continue;
    }
    const auto f = SplitOn(*body, ',');
    if (f[0].size() < 5 || f[0].substr(f[0].size() - 3) != "GGA") continue;
    ++gga;
    if (f.size() < 10) {
      throw Error(fmt::format("{}: GGA sentence has {} fields, expected at least 10",
                              where.Prefix(),
                              f.size()));
    }
    const int quality = f[6].empty() ? 0 : ParseInt(f[6], where, "GGA fix quality");
    if (quality == 0 || f[2].empty() || f[4].empty()) {
      ++no_fix;
      continue;
    }
    const double time_of_day = ParseNmeaTime(f[1], where);
    // Midnight: the time of day wraps around.
    if (last_time_of_day >= 0.0 && time_of_day < last_time_of_day - 43200.0) {
      day_offset_s += kSecondsPerDay;
    }
    last_time_of_day = time_of_day;
    Geodetic g;
    g.latitude_deg = ParseNmeaAngle(f[2], f[3], 2, where, "latitude");
    g.longitude_deg = ParseNmeaAngle(f[4], f[5], 3, where, "longitude");
    CheckLatLon(g.latitude_deg, g.longitude_deg, where);
    // Ellipsoidal height = altitude above mean sea level + geoid separation.
    const double altitude_m =
        f[9].empty() ? 0.0 : ParseNumber(f[9], where, "GGA altitude");
    const double separation_m = f.size() > 11 && !f[11].empty()
                                    ? ParseNumber(f[11], where, "GGA geoid separation")
                                    : 0.0;
    g.height_m = altitude_m + separation_m;
    builder.AddGeodetic(day_offset_s + time_of_day, g, quality, where);
  }
  if (bad_checksums > 0) {
    builder.track().warnings.push_back(
        fmt::format("{}: skipped {} sentences with a bad checksum (first at line {})",
                    origin,
                    bad_checksums,
                    first_bad_line));
  }
  if (no_fix > 0) {
    builder.track().warnings.push_back(
        fmt::format("{}: skipped {} GGA sentences without a fix", origin, no_fix));
  }
  if (gga == 0) {
    throw Error(
        fmt::format("{}: no GGA sentence (the reader uses $GPGGA/$GNGGA positions){}",
                    origin,
                    bad_checksums > 0
                        ? fmt::format("; {} sentences had a bad checksum", bad_checksums)
                        : std::string()));
  }
  builder.track().time_system = TimeSystem::kUtc;
  return builder.Finish("GGA fix");
}

// ------------------------------------------------------------------- CSV

int FindColumn(const std::vector<std::string>& names,
               std::initializer_list<const char*> aliases) {
  for (std::size_t i = 0; i < names.size(); ++i) {
    for (const char* alias : aliases) {
      if (names[i] == alias) return static_cast<int>(i);
    }
  }
  return -1;
}

GnssTrack ParseGnssCsv(const std::string& text,
                       const std::string& origin,
                       const GnssReadOptions& options) {
  TrackBuilder builder(origin, options);
  const auto lines = Lines(text);
  char delimiter = ',';
  std::vector<std::string> names;
  int t = -1, lat = -1, lon = -1, h = -1, e = -1, n = -1, u = -1, q = -1;
  std::size_t min_fields = 0;
  bool geodetic = false;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const Where where{origin, i + 1};
    const std::string_view line = Trim(lines[i]);
    if (line.empty() || line.front() == '#' || line.front() == '%') continue;
    if (names.empty()) {
      for (const char c : {',', ';', '\t'}) {
        if (line.find(c) != std::string_view::npos) {
          delimiter = c;
          break;
        }
      }
      if (line.find_first_of(",;\t") == std::string_view::npos) delimiter = ' ';
      const auto fields =
          delimiter == ' ' ? SplitWhitespace(line) : SplitOn(line, delimiter);
      for (const auto f : fields) {
        std::string name = Lower(f);
        // Drop a unit suffix: "lat[deg]", "e (m)".
        const std::size_t cut = name.find_first_of("[( ");
        if (cut != std::string::npos && cut > 0) name = name.substr(0, cut);
        names.push_back(name);
      }
      t = FindColumn(names, {"t", "time", "time_s", "timestamp", "t_s"});
      lat = FindColumn(names, {"lat", "latitude", "lat_deg", "latitude_deg"});
      lon = FindColumn(names,
                       {"lon", "lng", "long", "longitude", "lon_deg", "longitude_deg"});
      h = FindColumn(names, {"h", "height", "alt", "altitude", "height_m", "h_m"});
      e = FindColumn(names, {"e", "east", "e_m", "east_m"});
      n = FindColumn(names, {"n", "north", "n_m", "north_m"});
      u = FindColumn(names, {"u", "up", "u_m", "up_m"});
      q = FindColumn(names, {"q", "quality"});
      geodetic = lat >= 0 && lon >= 0;
      if (t < 0 || (!geodetic && (e < 0 || n < 0))) {
        throw Error(fmt::format(
            "{}: the first line must be a header naming the columns: t,lat,lon,h "
            "(degrees, metres) or t,e,n,u (metres); found '{}'",
            where.Prefix(),
            line));
      }
      for (const int c : {t, lat, lon, h, e, n, u, q}) {
        min_fields = std::max(min_fields, static_cast<std::size_t>(c + 1));
      }
      continue;
    }
    const auto fields =
        delimiter == ' ' ? SplitWhitespace(line) : SplitOn(line, delimiter);
    if (fields.size() < min_fields) {
      throw Error(fmt::format("{}: {} fields, the header names {}",
                              where.Prefix(),
                              fields.size(),
                              min_fields));
    }
    const double time_s = ParseNumber(fields[t], where, names[t]);
    const int quality = q >= 0 ? ParseInt(fields[q], where, names[q]) : 0;
    if (!builder.KeepQuality(quality, q >= 0)) continue;
    if (geodetic) {
      Geodetic g{ParseNumber(fields[lat], where, names[lat]),
                 ParseNumber(fields[lon], where, names[lon]),
                 h >= 0 ? ParseNumber(fields[h], where, names[h]) : 0.0};
      CheckLatLon(g.latitude_deg, g.longitude_deg, where);
      builder.AddGeodetic(time_s, g, quality, where);
    } else {
      builder.AddLocal(time_s,
                       {ParseNumber(fields[e], where, names[e]),
                        ParseNumber(fields[n], where, names[n]),
                        u >= 0 ? ParseNumber(fields[u], where, names[u]) : 0.0},
                       quality,
                       where,
                       /*relative=*/false);
    }
  }
  if (names.empty()) throw Error(fmt::format("{}: no header and no data", origin));
  builder.track().time_system = TimeSystem::kUnknown;
  return builder.Finish("data");
}

GnssFormat DetectFormat(const std::string& text, const std::string& origin) {
  for (const auto raw : Lines(text)) {
    const std::string_view line = Trim(raw);
    if (line.empty()) continue;
    if (line.find('$') != std::string_view::npos &&
        line.find("GGA") != std::string_view::npos) {
      return GnssFormat::kNmea;
    }
    if (line.front() == '$') return GnssFormat::kNmea;
    if (line.front() == '%') {
      const std::string lower = Lower(line);
      if (lower.find("gpst") != std::string::npos ||
          lower.find("utc") != std::string::npos ||
          lower.find("rtklib") != std::string::npos ||
          lower.find("program") != std::string::npos ||
          lower.find("jst") != std::string::npos) {
        return GnssFormat::kRtklibPos;
      }
      continue;
    }
    if (line.front() == '#') continue;
    if (std::isalpha(static_cast<unsigned char>(line.front()))) return GnssFormat::kCsv;
    break;
  }
  throw Error(fmt::format(
      "{}: cannot tell the format of the reference (not an RTKLIB .pos with its '%' "
      "header, "
      "not NMEA '$..GGA' sentences, not a CSV with a t,lat,lon,h or t,e,n,u header); "
      "name it with --gnss-format",
      origin));
}

}  // namespace

std::string_view ToString(TimeSystem system) {
  switch (system) {
    case TimeSystem::kGpst:
      return "gpst";
    case TimeSystem::kUtc:
      return "utc";
    case TimeSystem::kUnknown:
      break;
  }
  return "unknown";
}

std::string_view ToString(GnssFormat format) {
  switch (format) {
    case GnssFormat::kAuto:
      return "auto";
    case GnssFormat::kRtklibPos:
      return "pos";
    case GnssFormat::kNmea:
      return "nmea";
    case GnssFormat::kCsv:
      return "csv";
  }
  return "auto";
}

std::optional<GnssFormat> ParseGnssFormat(std::string_view name) {
  const std::string lower = Lower(name);
  if (lower == "auto") return GnssFormat::kAuto;
  if (lower == "pos" || lower == "rtklib") return GnssFormat::kRtklibPos;
  if (lower == "nmea") return GnssFormat::kNmea;
  if (lower == "csv") return GnssFormat::kCsv;
  return std::nullopt;
}

std::string GnssReadOptions::Validate() const {
  if (max_rtklib_quality < 0 || max_rtklib_quality > 6) {
    return "max_rtklib_quality must be 0 (keep all) or an RTKLIB Q of 1..6";
  }
  return "";
}

GnssTrack ParseGnss(const std::string& text,
                    const std::string& origin,
                    const GnssReadOptions& options) {
  if (const std::string problem = options.Validate(); !problem.empty()) {
    throw Error("GNSS reader options: " + problem);
  }
  if (Trim(text).empty())
    throw Error(fmt::format("{}: the reference file is empty", origin));
  const GnssFormat format =
      options.format == GnssFormat::kAuto ? DetectFormat(text, origin) : options.format;
  switch (format) {
    case GnssFormat::kRtklibPos:
      return ParseRtklibPos(text, origin, options);
    case GnssFormat::kNmea:
      return ParseNmea(text, origin, options);
    case GnssFormat::kCsv:
    case GnssFormat::kAuto:
      break;
  }
  return ParseGnssCsv(text, origin, options);
}

GnssTrack ReadGnss(const std::string& path, const GnssReadOptions& options) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw Error(fmt::format("{}: is a directory, not a GNSS reference file", path));
  }
  if (::access(path.c_str(), R_OK) != 0) {
    throw Error(fmt::format(
        "{}: cannot open the GNSS reference file (missing or unreadable)", path));
  }
  // Checked before it is read to the end (not a device, not binary, not
  // larger than a day of 10 Hz positions).
  return ParseGnss(
      ReadTextInput(path, kMaxReferenceFileBytes, "GNSS reference file"), path, options);
}

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

std::string FormatRtklibPos(const std::vector<PosEpoch>& epochs, TimeSystem time_system) {
  const char* system = time_system == TimeSystem::kUtc ? "UTC " : "GPST";
  std::string out;
  out += "% program   : mpcal simulate walk\n";
  out += "% pos mode  : kinematic\n";
  out +=
      "% (lat/lon/height=WGS84/ellipsoidal,Q=1:fix,2:float,3:sbas,4:dgps,5:single,6:ppp,"
      "ns=# of satellites)\n";
  out += fmt::format(
      "%  {}                  latitude(deg) longitude(deg)  height(m)   Q  ns   sdn(m)   "
      "sde(m)   sdu(m)  sdne(m)  sdeu(m)  sdun(m) age(s)  ratio\n",
      system);
  for (const PosEpoch& e : epochs) {
    // Round to the millisecond first so that 59.9996 s never prints as "60.000".
    const double ms_total = std::round(e.time_s * 1000.0);
    const double day = std::floor(ms_total / (kSecondsPerDay * 1000.0));
    const double ms_of_day = ms_total - day * kSecondsPerDay * 1000.0;
    const std::chrono::sys_days days{std::chrono::days{static_cast<int>(day)}};
    const std::chrono::year_month_day ymd{days};
    const auto ms = static_cast<long long>(ms_of_day);
    out += fmt::format(
        "{:04d}/{:02d}/{:02d} {:02d}:{:02d}:{:02d}.{:03d} {:14.9f} {:14.9f} {:10.4f} "
        "{:3d} {:3d} "
        "{:8.4f} {:8.4f} {:8.4f} {:8.4f} {:8.4f} {:8.4f} {:6.2f} {:6.1f}\n",
        static_cast<int>(ymd.year()),
        static_cast<unsigned>(ymd.month()),
        static_cast<unsigned>(ymd.day()),
        ms / 3600000,
        (ms / 60000) % 60,
        (ms / 1000) % 60,
        ms % 1000,
        e.position.latitude_deg,
        e.position.longitude_deg,
        e.position.height_m,
        e.quality,
        e.satellites,
        e.std_neu_m.x(),
        e.std_neu_m.y(),
        e.std_neu_m.z(),
        0.0,
        0.0,
        0.0,
        0.0,
        0.0);
  }
  return out;
}

}  // namespace mpcal
