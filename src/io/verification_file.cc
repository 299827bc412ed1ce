// The files of a field verification: the result JSON
// ("mpcal.verification/1") and the trajectory CSVs, each written and read
// here.
#include "mpcal/verification_file.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <sstream>
#include <string_view>

#include <fast_float/fast_float.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "io/json_reader.h"
#include "io/json_text.h"
#include "io/result_text.h"
#include "mpcal/error.h"
#include "text/text.h"

namespace mpcal {
namespace {

using json = JsonReader::json;

constexpr std::string_view kVerificationFamily = "mpcal.verification";
constexpr double kDegPerRad = 180.0 / std::numbers::pi;

// The file's words for the enums. They are the format's (version 1), not
// the command line's: a flag value renamed tomorrow leaves the files alone.
std::string_view FileWord(TimeAlignMode mode) {
  switch (mode) {
    case TimeAlignMode::kAuto:
      return "auto";
    case TimeAlignMode::kCommonClock:
      return "common";
    case TimeAlignMode::kOffset:
      return "offset";
    case TimeAlignMode::kMotionStart:
      return "motion";
  }
  return "auto";
}

std::string_view FileWord(MountMode mode) {
  return mode == MountMode::kZUp ? "z-up" : "level";
}

json MetricsJson(const PathMetrics& m) {
  return {{"start_end_distance_m", m.start_end_distance_m},
          {"horizontal_rms_m", m.horizontal_rms_m},
          {"horizontal_max_m", m.horizontal_max_m},
          {"path_length_m", m.path_length_m}};
}

json TimeAlignmentJson(const TimeAlignment& t) {
  json time = {{"method", FileWord(t.method)},
               {"offset_s", t.offset_s},
               {"overlap_start_s", t.overlap_start_s},
               {"overlap_end_s", t.overlap_end_s}};
  if (t.motion_offset_s) time["motion_offset_s"] = *t.motion_offset_s;
  return time;
}

json IntegrationJson(const VerifyResult& r) {
  return json{{"mount", FileWord(r.mount)},
              {"gravity_mps2", r.gravity_mps2},
              {"gyroscope", r.gyro_used},
              {"initial_rest_s", r.initial_rest_s},
              {"initial_tilt_raw_deg", r.initial_tilt_raw_rad * kDegPerRad},
              {"stops", r.stops},
              {"heading_rotation_deg", r.heading_rotation_rad * kDegPerRad},
              {"reference_epochs", r.reference.epochs}};
}

// A distance or a length (m): never negative (a corrupt or hand-edited
// file), as no reader lets an impossible value reach a table.
std::optional<double> Distance(const JsonReader& r,
                               const json& object,
                               const char* path,
                               const char* key,
                               bool required) {
  const std::optional<double> v =
      required ? r.Number(object, path, key) : r.OptionalNumber(object, path, key);
  if (v && !(*v >= 0.0)) {
    r.Fail(fmt::format("'{}.{}' = {} m is negative: not a distance", path, key, *v));
  }
  return v;
}

VerificationSummary::Metrics ReadMetrics(const JsonReader& r,
                                         const json& doc,
                                         const char* key) {
  const json& m = r.Object(doc, "", key);
  VerificationSummary::Metrics out;
  out.start_end_distance_m = *Distance(r, m, key, "start_end_distance_m", true);
  out.horizontal_rms_m = Distance(r, m, key, "horizontal_rms_m", false);
  out.horizontal_max_m = Distance(r, m, key, "horizontal_max_m", false);
  out.path_length_m = Distance(r, m, key, "path_length_m", false);
  return out;
}

// How the paths were made, and the warnings: informative, shown as they
// are, never required.
void ReadDetails(const json& doc, VerificationSummary& out) {
  for (const char* group : {"time_alignment", "integration"}) {
    const auto g = doc.find(group);
    if (g == doc.end() || !g->is_object()) continue;
    for (const auto& [key, value] : g->items()) {
      out.details.emplace_back(
          fmt::format("{}.{}", group, key),
          value.is_string() ? value.get<std::string>() : value.dump());
    }
  }
  if (const auto w = doc.find("warnings"); w != doc.end() && w->is_array()) {
    for (const json& line : *w) {
      if (line.is_string()) out.warnings.push_back(line.get<std::string>());
    }
  }
}

// Trajectory files the result names, relative to the result's directory.
void ReadTrajectoryFiles(const JsonReader& r,
                         const json& doc,
                         const std::string& origin,
                         VerificationSummary& out) {
  if (!doc.contains("trajectories")) return;
  const json& files = r.Object(doc, "", "trajectories");
  const std::filesystem::path base = std::filesystem::path(origin).parent_path();
  for (const char* role : {"reference", "raw", "corrected"}) {
    if (!files.contains(role)) continue;
    const std::filesystem::path p(r.String(files, "trajectories", role));
    out.trajectory_files.emplace_back(role,
                                      p.is_absolute() ? p.string() : (base / p).string());
  }
}

struct EastNorthColumns {
  int t = -1;
  int e = -1;
  int n = -1;
  bool complete() const { return t >= 0 && e >= 0 && n >= 0; }
};

EastNorthColumns FindColumns(const std::vector<std::string_view>& header) {
  EastNorthColumns cols;
  for (std::size_t i = 0; i < header.size(); ++i) {
    const std::string c = text::Lower(header[i]);
    const int idx = static_cast<int>(i);
    if (c == "t" || c == "t_s" || c == "time" || c == "time_s") cols.t = idx;
    if (c == "e" || c == "e_m" || c == "east" || c == "east_m") cols.e = idx;
    if (c == "n" || c == "n_m" || c == "north" || c == "north_m") cols.n = idx;
  }
  return cols;
}

double CsvNumber(std::string_view cell,
                 const std::string& path,
                 std::size_t line_no,
                 int column) {
  double v = 0.0;
  const auto res = fast_float::from_chars(cell.data(), cell.data() + cell.size(), v);
  if (res.ec != std::errc() || res.ptr != cell.data() + cell.size() ||
      !std::isfinite(v)) {
    throw Error(ErrorKind::kInput,
                fmt::format("{}:{}: column {}: \"{}\" is not a finite number",
                            path,
                            line_no,
                            column + 1,
                            cell));
  }
  return v;
}

bool SkippedLine(std::string_view line) {
  return text::Trim(line).empty() || line[0] == '#';
}

}  // namespace

std::string VerificationToJson(
    const VerifyResult& r,
    const std::vector<std::pair<std::string, std::string>>& trajectory_files) {
  json j;
  j["format"] = kVerificationFormat;
  j["reference"] = {{"path_length_m", r.reference.path_length_m},
                    {"start_end_distance_m", r.reference.start_end_distance_m}};
  j["raw"] = MetricsJson(r.raw);
  if (r.corrected) j["corrected"] = MetricsJson(*r.corrected);
  j["time_alignment"] = TimeAlignmentJson(r.time);
  j["integration"] = IntegrationJson(r);
  j["warnings"] = r.warnings;
  if (!trajectory_files.empty()) {
    json files;
    for (const auto& [role, path] : trajectory_files) files[role] = path;
    j["trajectories"] = files;
  }
  return FiniteJsonText(j, 2, "the verification result");
}

std::string PathToCsv(const TimedPath& path, const std::vector<int>& quality) {
  const bool with_q = quality.size() == path.size() && !quality.empty();
  std::string out = with_q ? "t_s,e_m,n_m,u_m,q\n" : "t_s,e_m,n_m,u_m\n";
  for (std::size_t i = 0; i < path.size(); ++i) {
    const Eigen::Vector3d& p = path.position_m[i];
    out +=
        fmt::format("{:.4f},{:.4f},{:.4f},{:.4f}", path.time_s[i], p.x(), p.y(), p.z());
    out += with_q ? fmt::format(",{}\n", quality[i]) : "\n";
  }
  return out;
}

VerificationSummary ParseVerificationJson(const std::string& text,
                                          const std::string& origin) {
  const JsonReader r(origin, Stage::kVerify);
  const json doc = r.Parse(text);
  r.ExpectFormat(doc, kVerificationFamily, 1);
  VerificationSummary out;
  const json& reference = r.Object(doc, "", "reference");
  out.reference.start_end_distance_m =
      *Distance(r, reference, "reference", "start_end_distance_m", true);
  out.reference.path_length_m =
      Distance(r, reference, "reference", "path_length_m", false);
  out.raw = ReadMetrics(r, doc, "raw");
  if (doc.contains("corrected")) out.corrected = ReadMetrics(r, doc, "corrected");
  ReadDetails(doc, out);
  ReadTrajectoryFiles(r, doc, origin, out);
  return out;
}

VerificationSummary ReadVerificationFile(const std::string& path) {
  return ParseVerificationJson(internal::ReadResultText(path, "a verification result"),
                               path);
}

EastNorthPath ReadEastNorthCsv(const std::string& path) {
  std::istringstream in(internal::ReadResultText(path, "a trajectory CSV"));
  std::string line;
  std::size_t line_no = 0;
  EastNorthColumns cols;
  while (std::getline(in, line)) {
    ++line_no;
    if (SkippedLine(line)) continue;
    cols = FindColumns(text::SplitOn(line, ','));
    break;
  }
  if (!cols.complete()) {
    throw Error(
        ErrorKind::kInput,
        fmt::format("{}:{}: expected a header naming the time (t, time_s), east (e, "
                    "east_m) and north (n, north_m) columns",
                    path,
                    line_no));
  }
  const std::size_t need =
      static_cast<std::size_t>(std::max({cols.t, cols.e, cols.n})) + 1;
  EastNorthPath out;
  while (std::getline(in, line)) {
    ++line_no;
    if (SkippedLine(line)) continue;
    const std::vector<std::string_view> cells = text::SplitOn(line, ',');
    if (cells.size() < need) {
      throw Error(ErrorKind::kInput,
                  fmt::format("{}:{}: {} columns, expected at least {}",
                              path,
                              line_no,
                              cells.size(),
                              need));
    }
    out.time_s.push_back(
        CsvNumber(cells[static_cast<std::size_t>(cols.t)], path, line_no, cols.t));
    out.east_m.push_back(
        CsvNumber(cells[static_cast<std::size_t>(cols.e)], path, line_no, cols.e));
    out.north_m.push_back(
        CsvNumber(cells[static_cast<std::size_t>(cols.n)], path, line_no, cols.n));
  }
  if (out.time_s.empty())
    throw Error(ErrorKind::kInput, fmt::format("{}: no data rows", path));
  return out;
}

}  // namespace mpcal
