// Reading a GNSS reference track: the format told from the first lines (or
// given), then the reader of that format (rtklib_pos.cc, nmea.cc,
// gnss_csv.cc).
#include <unistd.h>

#include <cctype>
#include <filesystem>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>

#include <fmt/format.h>

#include "gnss/gnss_fields.h"
#include "mpcal/advice.h"
#include "mpcal/error.h"
#include "mpcal/gnss.h"
#include "mpcal/text_input.h"
#include "text/text.h"

namespace mpcal {
namespace {

GnssFormat DetectFormat(const std::string& text, const std::string& origin) {
  for (const auto raw : text::Lines(text)) {
    const std::string_view line = text::Trim(raw);
    if (line.empty()) continue;
    if (line.find('$') != std::string_view::npos &&
        line.find("GGA") != std::string_view::npos) {
      return GnssFormat::kNmea;
    }
    if (line.front() == '$') return GnssFormat::kNmea;
    if (line.front() == '%') {
      const std::string lower = text::Lower(line);
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
  Advice advice;
  advice.settings.push_back({Option::kGnssFormat, ""});
  throw Error(ErrorKind::kFormat,
              fmt::format("{}: cannot tell the format of the reference (not an RTKLIB "
                          ".pos with its '%' header, not NMEA '$..GGA' sentences, not a "
                          "CSV with a t,lat,lon,h or t,e,n,u header)",
                          origin),
              std::move(advice));
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
  const std::string lower = text::Lower(name);
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
  if (text::Trim(text).empty())
    throw Error(fmt::format("{}: the reference file is empty", origin));
  const GnssFormat format =
      options.format == GnssFormat::kAuto ? DetectFormat(text, origin) : options.format;
  switch (format) {
    case GnssFormat::kRtklibPos:
      return gnss_internal::ParseRtklibPos(text, origin, options);
    case GnssFormat::kNmea:
      return gnss_internal::ParseNmea(text, origin, options);
    case GnssFormat::kCsv:
    case GnssFormat::kAuto:
      break;
  }
  return gnss_internal::ParseGnssCsv(text, origin, options);
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

}  // namespace mpcal
