// RTKLIB .pos solutions: read (geodetic in degrees or d m s, ECEF, or ENU
// baselines; calendar or GPS week time; GPST, UTC or JST) and written.
#include <chrono>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gnss/gnss_fields.h"
#include "mpcal/error.h"
#include "text/text.h"

namespace mpcal {
namespace gnss_internal {
namespace {

enum class PosLayout { kGeodeticDeg, kGeodeticDms, kEcef, kEnu };

// What the column header says: the layout of a row and its clock.
struct PosHeader {
  std::optional<PosLayout> layout;
  TimeSystem system = TimeSystem::kGpst;
  double clock_shift_s = 0.0;  // JST is UTC + 9 h
};

// A '%' line: the column header sets the layout and the clock; other
// comment lines are skipped.
void ReadHeaderLine(std::string_view line, PosHeader& header) {
  const std::string lower = text::Lower(line);
  const auto has = [&](const char* word) {
    return lower.find(word) != std::string::npos;
  };
  if (!has("gpst") && !has("utc") && !has("jst")) return;
  if (has("latitude(d'")) {
    header.layout = PosLayout::kGeodeticDms;
  } else if (has("latitude")) {
    header.layout = PosLayout::kGeodeticDeg;
  } else if (has("x-ecef")) {
    header.layout = PosLayout::kEcef;
  } else if (has("e-baseline")) {
    header.layout = PosLayout::kEnu;
  } else {
    return;  // e.g. "% obs start : 2025/08/28 17:30:39.7 GPST ..."
  }
  header.system = has("utc") || has("jst") ? TimeSystem::kUtc : TimeSystem::kGpst;
  header.clock_shift_s = has("utc") || !has("jst") ? 0.0 : -9.0 * 3600.0;
}

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

// The epoch's time: a calendar date and time, or GPS week and time of week
// (RTKLIB's time format "tow").
double EpochTime(const std::vector<std::string_view>& tokens, const Where& where) {
  if (tokens[0].find('/') != std::string_view::npos ||
      tokens[0].find('-') != std::string_view::npos) {
    return ParseCalendar(tokens[0], tokens[1], where);
  }
  const int week = ParseInt(tokens[0], where, "GPS week");
  const double tow = ParseNumber(tokens[1], where, "time of week");
  if (week < 0 || tow < 0.0 || tow >= kSecondsPerWeek) {
    throw Error(fmt::format("{}: GPS week {} / time of week {} s is out of range",
                            where.Prefix(),
                            tokens[0],
                            tokens[1]));
  }
  return kGpsEpochS + week * kSecondsPerWeek + tow;
}

void AddPosition(TrackBuilder& builder,
                 PosLayout layout,
                 const std::vector<std::string_view>& tokens,
                 double time_s,
                 int quality,
                 const Where& where) {
  const auto number = [&](std::size_t i, std::string_view field) {
    return ParseNumber(tokens[i], where, field);
  };
  switch (layout) {
    case PosLayout::kGeodeticDeg: {
      const Geodetic g{
          number(2, "latitude"), number(3, "longitude"), number(4, "height")};
      CheckLatLon(g.latitude_deg, g.longitude_deg, where);
      builder.AddGeodetic(time_s, g, quality, where);
      return;
    }
    case PosLayout::kGeodeticDms: {
      const Geodetic g{ParseDms(tokens[2], tokens[3], tokens[4], where, "latitude"),
                       ParseDms(tokens[5], tokens[6], tokens[7], where, "longitude"),
                       number(8, "height")};
      CheckLatLon(g.latitude_deg, g.longitude_deg, where);
      builder.AddGeodetic(time_s, g, quality, where);
      return;
    }
    case PosLayout::kEcef:
      builder.AddEcef(time_s,
                      {number(2, "x-ecef"), number(3, "y-ecef"), number(4, "z-ecef")},
                      quality,
                      where);
      return;
    case PosLayout::kEnu:
      builder.AddLocal(
          time_s,
          {number(2, "e-baseline"), number(3, "n-baseline"), number(4, "u-baseline")},
          quality,
          where,
          /*relative=*/true);
      return;
  }
}

void ReadRow(std::string_view line,
             const PosHeader& header,
             const Where& where,
             TrackBuilder& builder) {
  if (!header.layout) {
    throw Error(fmt::format(
        "{}: data before the column header; an RTKLIB .pos file has a header line "
        "like '%  GPST  latitude(deg) longitude(deg) height(m) Q ns ...' (write the "
        "solution with the header on, out-head=on)",
        where.Prefix()));
  }
  const auto tokens = text::SplitWhitespace(line);
  // dd mm ss.s dd mm ss.s height, or three numbers.
  const std::size_t position_tokens = *header.layout == PosLayout::kGeodeticDms ? 7 : 3;
  const std::size_t needed = 2 + position_tokens + 1;  // time, position, Q
  if (tokens.size() < needed) {
    throw Error(fmt::format("{}: {} fields, expected at least {} (time, position, Q)",
                            where.Prefix(),
                            tokens.size(),
                            needed));
  }
  const double time_s = EpochTime(tokens, where) + header.clock_shift_s;
  const int quality = ParseInt(tokens[2 + position_tokens], where, "Q");
  if (!builder.KeepQuality(quality, true)) return;
  AddPosition(builder, *header.layout, tokens, time_s, quality, where);
}

}  // namespace

GnssTrack ParseRtklibPos(const std::string& text,
                         const std::string& origin,
                         const GnssReadOptions& options) {
  TrackBuilder builder(origin, options);
  PosHeader header;
  const auto lines = text::Lines(text);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string_view line = text::Trim(lines[i]);
    if (line.empty()) continue;
    if (line.front() == '%') {
      ReadHeaderLine(line, header);
      continue;
    }
    ReadRow(line, header, Where{origin, i + 1}, builder);
  }
  if (!header.layout) {
    throw Error(fmt::format(
        "{}: no RTKLIB column header (a line like '%  GPST  latitude(deg) longitude(deg) "
        "height(m) Q ...'); is it a .pos file?",
        origin));
  }
  builder.track().time_system = header.system;
  return builder.Finish("position");
}

}  // namespace gnss_internal

std::string FormatRtklibPos(const std::vector<PosEpoch>& epochs,
                            TimeSystem time_system,
                            std::string_view program) {
  const char* system = time_system == TimeSystem::kUtc ? "UTC " : "GPST";
  std::string out;
  out += fmt::format("% program   : {}\n", program);
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
    const double day = std::floor(ms_total / (gnss_internal::kSecondsPerDay * 1000.0));
    const double ms_of_day = ms_total - day * gnss_internal::kSecondsPerDay * 1000.0;
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
