// CSV references: a header naming t,lat,lon[,h][,q] (degrees, metres) or
// t,e,n[,u][,q] (metres), delimited by commas, semicolons, tabs or spaces.
#include <algorithm>
#include <initializer_list>
#include <string>
#include <string_view>
#include <vector>

#include "gnss/gnss_fields.h"
#include "mpcal/error.h"
#include "text/text.h"

namespace mpcal::gnss_internal {
namespace {

int FindColumn(const std::vector<std::string>& names,
               std::initializer_list<const char*> aliases) {
  for (std::size_t i = 0; i < names.size(); ++i) {
    for (const char* alias : aliases) {
      if (names[i] == alias) return static_cast<int>(i);
    }
  }
  return -1;
}

// The header: the delimiter, the column names and where each quantity is
// (-1: absent).
struct CsvLayout {
  char delimiter = ',';
  std::vector<std::string> names;
  int t = -1, lat = -1, lon = -1, h = -1, e = -1, n = -1, u = -1, q = -1;
  std::size_t min_fields = 0;
  bool geodetic = false;

  std::vector<std::string_view> Split(std::string_view line) const {
    return delimiter == ' ' ? text::SplitWhitespace(line)
                            : text::SplitOn(line, delimiter);
  }
};

char Delimiter(std::string_view line) {
  for (const char c : {',', ';', '\t'}) {
    if (line.find(c) != std::string_view::npos) return c;
  }
  return ' ';
}

CsvLayout ReadHeader(std::string_view line, const Where& where) {
  CsvLayout l;
  l.delimiter = Delimiter(line);
  for (const auto f : l.Split(line)) {
    std::string name = text::Lower(f);
    // Drop a unit suffix: "lat[deg]", "e (m)".
    const std::size_t cut = name.find_first_of("[( ");
    if (cut != std::string::npos && cut > 0) name = name.substr(0, cut);
    l.names.push_back(name);
  }
  l.t = FindColumn(l.names, {"t", "time", "time_s", "timestamp", "t_s"});
  l.lat = FindColumn(l.names, {"lat", "latitude", "lat_deg", "latitude_deg"});
  l.lon = FindColumn(l.names,
                     {"lon", "lng", "long", "longitude", "lon_deg", "longitude_deg"});
  l.h = FindColumn(l.names, {"h", "height", "alt", "altitude", "height_m", "h_m"});
  l.e = FindColumn(l.names, {"e", "east", "e_m", "east_m"});
  l.n = FindColumn(l.names, {"n", "north", "n_m", "north_m"});
  l.u = FindColumn(l.names, {"u", "up", "u_m", "up_m"});
  l.q = FindColumn(l.names, {"q", "quality"});
  l.geodetic = l.lat >= 0 && l.lon >= 0;
  if (l.t < 0 || (!l.geodetic && (l.e < 0 || l.n < 0))) {
    throw Error(
        ErrorKind::kColumns,
        fmt::format("{}: the first line must be a header naming the columns: "
                    "t,lat,lon,h (degrees, metres) or t,e,n,u (metres); found '{}'",
                    where.Prefix(),
                    line));
  }
  for (const int c : {l.t, l.lat, l.lon, l.h, l.e, l.n, l.u, l.q}) {
    l.min_fields = std::max(l.min_fields, static_cast<std::size_t>(c + 1));
  }
  return l;
}

void ReadRow(std::string_view line,
             const CsvLayout& l,
             const Where& where,
             TrackBuilder& builder) {
  const auto fields = l.Split(line);
  if (fields.size() < l.min_fields) {
    throw Error(fmt::format("{}: {} fields, the header names {}",
                            where.Prefix(),
                            fields.size(),
                            l.min_fields));
  }
  // Column `c` as a number; `fallback` when the column is absent.
  const auto number = [&](int c, double fallback) {
    if (c < 0) return fallback;
    const auto i = static_cast<std::size_t>(c);
    return ParseNumber(fields[i], where, l.names[i]);
  };
  const double time_s = number(l.t, 0.0);
  const int quality = l.q >= 0 ? ParseInt(fields[static_cast<std::size_t>(l.q)],
                                          where,
                                          l.names[static_cast<std::size_t>(l.q)])
                               : 0;
  if (!builder.KeepQuality(quality, l.q >= 0)) return;
  if (l.geodetic) {
    const Geodetic g{number(l.lat, 0.0), number(l.lon, 0.0), number(l.h, 0.0)};
    CheckLatLon(g.latitude_deg, g.longitude_deg, where);
    builder.AddGeodetic(time_s, g, quality, where);
  } else {
    builder.AddLocal(time_s,
                     {number(l.e, 0.0), number(l.n, 0.0), number(l.u, 0.0)},
                     quality,
                     where,
                     /*relative=*/false);
  }
}

}  // namespace

GnssTrack ParseGnssCsv(const std::string& text,
                       const std::string& origin,
                       const GnssReadOptions& options) {
  TrackBuilder builder(origin, options);
  std::optional<CsvLayout> layout;
  const auto lines = text::Lines(text);
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const Where where{origin, i + 1};
    const std::string_view line = text::Trim(lines[i]);
    if (line.empty() || line.front() == '#' || line.front() == '%') continue;
    if (!layout) {
      layout = ReadHeader(line, where);
    } else {
      ReadRow(line, *layout, where, builder);
    }
  }
  if (!layout) throw Error(fmt::format("{}: no header and no data", origin));
  builder.track().time_system = TimeSystem::kUnknown;
  return builder.Finish("data");
}

}  // namespace mpcal::gnss_internal
