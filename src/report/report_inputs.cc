// Reading the report's inputs: the verification JSON of `mpcal verify`,
// trajectory CSVs, and the whole set of files behind a report.
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <fast_float/fast_float.h>
#include <fmt/format.h>

#include "mpcal/calibration_file.h"
#include "mpcal/error.h"
#include "mpcal/json_reader.h"
#include "mpcal/repeat.h"
#include "mpcal/report.h"
#include "mpcal/text_input.h"

namespace mpcal {

namespace {

using json = JsonReader::json;

constexpr std::string_view kVerificationFamily = "mpcal.verification";

VerificationSummary::Metrics ReadMetrics(const JsonReader& r,
                                         const json& doc,
                                         const char* key) {
  const json& m = r.Object(doc, "", key);
  VerificationSummary::Metrics out;
  out.start_end_distance_m = r.Number(m, key, "start_end_distance_m");
  out.horizontal_rms_m = r.OptionalNumber(m, key, "horizontal_rms_m");
  out.horizontal_max_m = r.OptionalNumber(m, key, "horizontal_max_m");
  out.path_length_m = r.OptionalNumber(m, key, "path_length_m");
  return out;
}

std::string ReadText(const std::string& path, const char* what) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw Error(fmt::format("{}: is a directory, expected {}", path, what));
  }
  if (::access(path.c_str(), R_OK) != 0) {
    throw Error(fmt::format("{}: cannot open {} (does it exist?)", path, what));
  }
  std::string_view kind(what);
  if (kind.starts_with("a ")) kind.remove_prefix(2);
  return ReadTextInput(
      path, kind.ends_with("CSV") ? kMaxReferenceFileBytes : kMaxResultFileBytes, kind);
}

std::vector<std::string> SplitCsv(const std::string& line) {
  std::vector<std::string> out;
  std::string cell;
  std::istringstream in(line);
  while (std::getline(in, cell, ',')) {
    while (!cell.empty() && (cell.back() == ' ' || cell.back() == '\r')) cell.pop_back();
    const auto first = cell.find_first_not_of(' ');
    out.push_back(first == std::string::npos ? std::string() : cell.substr(first));
  }
  return out;
}

std::string Lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

}  // namespace

VerificationSummary ParseVerificationJson(const std::string& text,
                                          const std::string& origin) {
  const JsonReader r(origin, "mpcal verify");
  const json doc = r.Parse(text);
  r.ExpectFormat(doc, kVerificationFamily, 1);
  VerificationSummary out;
  const json& reference = r.Object(doc, "", "reference");
  out.reference.start_end_distance_m =
      r.Number(reference, "reference", "start_end_distance_m");
  out.reference.path_length_m = r.OptionalNumber(reference, "reference", "path_length_m");
  out.raw = ReadMetrics(r, doc, "raw");
  if (doc.contains("corrected")) out.corrected = ReadMetrics(r, doc, "corrected");
  // The rest is informative: shown as it is, never required.
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
  // Trajectory files the result names, relative to the result's directory.
  if (doc.contains("trajectories")) {
    const json& files = r.Object(doc, "", "trajectories");
    const std::filesystem::path base = std::filesystem::path(origin).parent_path();
    for (const char* role : {"reference", "raw", "corrected"}) {
      if (!files.contains(role)) continue;
      const std::filesystem::path p(r.String(files, "trajectories", role));
      out.trajectory_files.emplace_back(
          role, p.is_absolute() ? p.string() : (base / p).string());
    }
  }
  return out;
}

EastNorthPath ReadEastNorthCsv(const std::string& path) {
  std::istringstream in(ReadText(path, "a trajectory CSV"));
  std::string line;
  std::size_t line_no = 0;
  int t_col = -1;
  int e_col = -1;
  int n_col = -1;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty() || line[0] == '#' || line == "\r") continue;
    const std::vector<std::string> cells = SplitCsv(line);
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const std::string c = Lower(cells[i]);
      const int idx = static_cast<int>(i);
      if (c == "t" || c == "t_s" || c == "time" || c == "time_s") t_col = idx;
      if (c == "e" || c == "e_m" || c == "east" || c == "east_m") e_col = idx;
      if (c == "n" || c == "n_m" || c == "north" || c == "north_m") n_col = idx;
    }
    break;
  }
  if (t_col < 0 || e_col < 0 || n_col < 0) {
    throw Error(fmt::format(
        "{}:{}: expected a header naming the time (t, time_s), east (e, east_m) and "
        "north (n, north_m) columns",
        path,
        line_no));
  }
  const std::size_t need = static_cast<std::size_t>(std::max({t_col, e_col, n_col})) + 1;
  EastNorthPath out;
  while (std::getline(in, line)) {
    ++line_no;
    if (line.empty() || line[0] == '#' || line == "\r") continue;
    const std::vector<std::string> cells = SplitCsv(line);
    if (cells.size() < need) {
      throw Error(fmt::format(
          "{}:{}: {} columns, expected at least {}", path, line_no, cells.size(), need));
    }
    double v[3];
    const int cols[3] = {t_col, e_col, n_col};
    for (int k = 0; k < 3; ++k) {
      const std::string& c = cells[static_cast<std::size_t>(cols[k])];
      const auto res = fast_float::from_chars(c.data(), c.data() + c.size(), v[k]);
      if (res.ec != std::errc() || res.ptr != c.data() + c.size() ||
          !std::isfinite(v[k])) {
        throw Error(fmt::format("{}:{}: column {}: \"{}\" is not a finite number",
                                path,
                                line_no,
                                cols[k] + 1,
                                c));
      }
    }
    out.time_s.push_back(v[0]);
    out.east_m.push_back(v[1]);
    out.north_m.push_back(v[2]);
  }
  if (out.time_s.empty()) throw Error(fmt::format("{}: no data rows", path));
  return out;
}

VerificationSummary SummarizeVerification(const VerifyResult& r) {
  VerificationSummary out;
  out.reference.start_end_distance_m = r.reference.start_end_distance_m;
  out.reference.path_length_m = r.reference.path_length_m;
  auto metrics = [](const PathMetrics& m) {
    return VerificationSummary::Metrics{
        m.start_end_distance_m, m.horizontal_rms_m, m.horizontal_max_m, m.path_length_m};
  };
  auto path = [](const TimedPath& p) {
    EastNorthPath en;
    en.time_s = p.time_s;
    for (const Eigen::Vector3d& x : p.position_m) {
      en.east_m.push_back(x.x());
      en.north_m.push_back(x.y());
    }
    return en;
  };
  out.raw = metrics(r.raw);
  if (r.corrected) out.corrected = metrics(*r.corrected);
  if (!r.reference_path.empty()) out.reference_path = path(r.reference_path);
  if (!r.raw_path.empty()) out.raw_path = path(r.raw_path);
  if (r.corrected_path && !r.corrected_path->empty()) {
    out.corrected_path = path(*r.corrected_path);
  }
  out.details = {
      {"time_alignment.offset_s", fmt::format("{:.3f}", r.time.offset_s)},
      {"integration.mount", r.mount == MountMode::kZUp ? "z-up" : "level"},
      {"integration.gravity_mps2", fmt::format("{:.5f}", r.gravity_mps2)},
      {"integration.gyroscope", r.gyro_used ? "true" : "false"},
      {"integration.initial_rest_s", fmt::format("{:.1f}", r.initial_rest_s)},
      {"integration.stops", std::to_string(r.stops)},
  };
  out.warnings = r.warnings;
  return out;
}

std::string ReportFiles::Validate() const {
  if (calibration.empty() && session.empty() && repeatability.empty() &&
      verification.empty() && noise.empty()) {
    return "no input: give at least one of calibration, session, repeatability, "
           "verification, noise";
  }
  if (!verification_trajectories.empty() && verification.empty()) {
    return "verification_trajectories needs verification";
  }
  if (const std::string e = log.Validate(); !e.empty()) return "log." + e;
  if (const std::string e = detect.Validate(); !e.empty()) return "detect." + e;
  return "";
}

ReportInputs LoadReportInputs(const ReportFiles& files) {
  if (const std::string e = files.Validate(); !e.empty()) {
    throw Error("report inputs: " + e);
  }
  ReportInputs in;
  if (!files.calibration.empty()) {
    in.calibration = ReadCalibrationFile(files.calibration);
    in.input_files.emplace_back("Calibration file", files.calibration);
  }
  if (!files.session.empty()) {
    ReportSession s;
    s.recording = ReadLog(files.session, files.log);
    s.detection = DetectStatic(s.recording, files.detect);
    in.session = std::move(s);
    in.input_files.emplace_back("Session log", files.session);
  }
  if (!files.repeatability.empty()) {
    in.repeatability = RepeatabilityFromJson(
        ReadText(files.repeatability, "a repeatability file"), files.repeatability);
    in.input_files.emplace_back("Repeatability table", files.repeatability);
  }
  if (!files.verification.empty()) {
    VerificationSummary v = ParseVerificationJson(
        ReadText(files.verification, "a verification result"), files.verification);
    in.input_files.emplace_back("Verification result", files.verification);
    std::vector<std::pair<std::string, std::string>> trajectories = v.trajectory_files;
    if (!files.verification_trajectories.empty()) {
      trajectories.clear();
      for (const char* role : {"reference", "raw", "corrected"}) {
        const std::string p = files.verification_trajectories + "-" + role + ".csv";
        // The corrected path exists only for a verification with a calibration.
        if (std::string(role) == "corrected" && !std::filesystem::exists(p)) continue;
        trajectories.emplace_back(role, p);
      }
    }
    for (const auto& [role, p] : trajectories) {
      EastNorthPath path = ReadEastNorthCsv(p);
      if (role == "reference") v.reference_path = std::move(path);
      if (role == "raw") v.raw_path = std::move(path);
      if (role == "corrected") v.corrected_path = std::move(path);
      in.input_files.emplace_back("Trajectory (" + role + ")", p);
    }
    in.verification = std::move(v);
  }
  if (!files.noise.empty()) {
    in.noise = ReadNoiseFile(files.noise);
    in.input_files.emplace_back("Noise analysis", files.noise);
  }
  return in;
}

}  // namespace mpcal
