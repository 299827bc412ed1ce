// The whole set of files behind a report, each read by its format's reader
// in io, and the summary of an in-memory verification.
#include <filesystem>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "mpcal/calibration_file.h"
#include "mpcal/error.h"
#include "mpcal/repeatability_file.h"
#include "mpcal/report.h"
#include "mpcal/verification_file.h"

namespace mpcal {

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
    in.repeatability = ReadRepeatabilityFile(files.repeatability);
    in.input_files.emplace_back("Repeatability table", files.repeatability);
  }
  if (!files.verification.empty()) {
    VerificationSummary v = ReadVerificationFile(files.verification);
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
      if (role == "reference") {
        v.reference_path = std::move(path);
      } else if (role == "raw") {
        v.raw_path = std::move(path);
      } else if (role == "corrected") {
        v.corrected_path = std::move(path);
      }
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
