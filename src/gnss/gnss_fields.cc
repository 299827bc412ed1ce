// The fields the GNSS formats share: numbers, integers, latitude and
// longitude, calendar dates and times.
#include "gnss/gnss_fields.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include <fast_float/fast_float.h>

#include "mpcal/error.h"
#include "text/text.h"

namespace mpcal::gnss_internal {

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
  const auto ymd = text::SplitOn(d, '/');
  const auto hms = text::SplitOn(time, ':');
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

}  // namespace mpcal::gnss_internal
