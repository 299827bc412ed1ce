// NMEA 0183 GGA positions, dated by RMC or ZDA sentences.
#include <charconv>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "gnss/gnss_fields.h"
#include "mpcal/error.h"
#include "text/text.h"

namespace mpcal::gnss_internal {
namespace {

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
  const std::string_view sum = text::Trim(sentence.substr(star + 1));
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

// The date of the first RMC (ddmmyy) or ZDA sentence, as seconds since
// 1970-01-01 of its midnight. GGA has only the time of day.
std::optional<double> FirstDate(const std::vector<std::string_view>& lines,
                                const std::string& origin) {
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::size_t dollar = lines[i].find('$');
    if (dollar == std::string_view::npos) continue;
    const auto body = NmeaBody(lines[i].substr(dollar));
    if (!body || body->size() < 6) continue;
    const auto f = text::SplitOn(*body, ',');
    const Where where{origin, i + 1};
    const std::string_view type = f[0].substr(f[0].size() >= 3 ? f[0].size() - 3 : 0);
    if (type == "RMC" && f.size() > 9 && f[9].size() == 6) {
      const int dd = ParseInt(f[9].substr(0, 2), where, "RMC day");
      const int mm = ParseInt(f[9].substr(2, 2), where, "RMC month");
      const int yy = ParseInt(f[9].substr(4, 2), where, "RMC year");
      return CalendarSeconds(yy < 80 ? 2000 + yy : 1900 + yy, mm, dd, 0.0, where);
    }
    if (type == "ZDA" && f.size() > 4 && !f[2].empty()) {
      return CalendarSeconds(ParseInt(f[4], where, "ZDA year"),
                             ParseInt(f[3], where, "ZDA month"),
                             ParseInt(f[2], where, "ZDA day"),
                             0.0,
                             where);
    }
  }
  return std::nullopt;
}

// What the sentences were, for the warnings and the empty-track message.
struct NmeaTally {
  int bad_checksums = 0;
  std::size_t first_bad_line = 0;
  int no_fix = 0;
  int gga = 0;
};

// The clock of GGA epochs: the date, advanced a day when the time of day
// wraps around at midnight.
struct NmeaClock {
  double day_offset_s = 0.0;
  double last_time_of_day = -1.0;

  double Time(double time_of_day) {
    if (last_time_of_day >= 0.0 && time_of_day < last_time_of_day - 43200.0) {
      day_offset_s += kSecondsPerDay;
    }
    last_time_of_day = time_of_day;
    return day_offset_s + time_of_day;
  }
};

void ReadGga(const std::vector<std::string_view>& f,
             const Where& where,
             NmeaClock& clock,
             NmeaTally& tally,
             TrackBuilder& builder) {
  ++tally.gga;
  if (f.size() < 10) {
    throw Error(fmt::format("{}: GGA sentence has {} fields, expected at least 10",
                            where.Prefix(),
                            f.size()));
  }
  const int quality = f[6].empty() ? 0 : ParseInt(f[6], where, "GGA fix quality");
  if (quality == 0 || f[2].empty() || f[4].empty()) {
    ++tally.no_fix;
    return;
  }
  const double time_s = clock.Time(ParseNmeaTime(f[1], where));
  Geodetic g;
  g.latitude_deg = ParseNmeaAngle(f[2], f[3], 2, where, "latitude");
  g.longitude_deg = ParseNmeaAngle(f[4], f[5], 3, where, "longitude");
  CheckLatLon(g.latitude_deg, g.longitude_deg, where);
  // Ellipsoidal height = altitude above mean sea level + geoid separation.
  const double altitude_m = f[9].empty() ? 0.0 : ParseNumber(f[9], where, "GGA altitude");
  const double separation_m = f.size() > 11 && !f[11].empty()
                                  ? ParseNumber(f[11], where, "GGA geoid separation")
                                  : 0.0;
  g.height_m = altitude_m + separation_m;
  builder.AddGeodetic(time_s, g, quality, where);
}

void AddWarnings(const NmeaTally& tally, const std::string& origin, GnssTrack& track) {
  if (tally.bad_checksums > 0) {
    track.warnings.push_back(
        fmt::format("{}: skipped {} sentences with a bad checksum (first at line {})",
                    origin,
                    tally.bad_checksums,
                    tally.first_bad_line));
  }
  if (tally.no_fix > 0) {
    track.warnings.push_back(
        fmt::format("{}: skipped {} GGA sentences without a fix", origin, tally.no_fix));
  }
}

}  // namespace

GnssTrack ParseNmea(const std::string& text,
                    const std::string& origin,
                    const GnssReadOptions& options) {
  TrackBuilder builder(origin, options);
  const auto lines = text::Lines(text);
  // Epochs before the first dated sentence take that first date.
  const std::optional<double> day_start_s = FirstDate(lines, origin);
  if (!day_start_s) {
    builder.track().warnings.push_back(fmt::format(
        "{}: no date (no RMC or ZDA sentence); times are seconds of the day from "
        "1970-01-01, so align the clocks by a time offset or by the start of motion",
        origin));
  }
  NmeaClock clock{day_start_s.value_or(0.0)};
  NmeaTally tally;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::size_t dollar = lines[i].find('$');
    if (dollar == std::string_view::npos) continue;
    const auto body = NmeaBody(text::Trim(lines[i].substr(dollar)));
    if (!body) {
      if (tally.bad_checksums++ == 0) tally.first_bad_line = i + 1;
      continue;
    }
    const auto f = text::SplitOn(*body, ',');
    if (f[0].size() < 5 || f[0].substr(f[0].size() - 3) != "GGA") continue;
    ReadGga(f, Where{origin, i + 1}, clock, tally, builder);
  }
  AddWarnings(tally, origin, builder.track());
  if (tally.gga == 0) {
    throw Error(fmt::format(
        "{}: no GGA sentence (the reader uses $GPGGA/$GNGGA positions){}",
        origin,
        tally.bad_checksums > 0
            ? fmt::format("; {} sentences had a bad checksum", tally.bad_checksums)
            : std::string()));
  }
  builder.track().time_system = TimeSystem::kUtc;
  return builder.Finish("GGA fix");
}

}  // namespace mpcal::gnss_internal
