/// \file report.h
/// \brief The report: one self-contained HTML page (inline SVG and CSS,
/// nothing fetched from the network) that shows a calibration and, when they
/// are given, the session it came from, its repeatability across sessions and
/// its verification against GNSS.
///
/// Each section appears exactly when its input is present in ReportInputs.
/// Values are SI inside; the page shows the paper's units (bias in mg and
/// m/s², scale-factor error in ppm, non-orthogonality in mrad).
#pragma once

#include <array>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "mpcal/advice.h"
#include "mpcal/calibration.h"
#include "mpcal/detect.h"
#include "mpcal/log_reader.h"
#include "mpcal/model.h"
#include "mpcal/noise_file.h"
#include "mpcal/recording.h"
#include "mpcal/repeat.h"
#include "mpcal/verification_file.h"
#include "mpcal/verify.h"

namespace mpcal {

/// The summary of an in-memory verification, paths included (east and north
/// of the reference's frame).
VerificationSummary SummarizeVerification(const VerifyResult& result);

/// The recording a calibration came from, and the static intervals in it.
struct ReportSession {
  Recording recording;
  DetectResult detection;
};

/// Everything a report can show; every part is optional.
struct ReportInputs {
  std::optional<Calibration> calibration;
  std::optional<ReportSession> session;
  /// From AnalyzeRepeatability, or RepeatabilityFromJson (which has no
  /// per-trial 1σ: the spread is then shown in the parameters' units).
  std::optional<RepeatabilityResult> repeatability;
  std::optional<VerificationSummary> verification;
  /// From `mpcal noise --json` (ReadNoiseFile).
  std::optional<NoiseFile> noise;
  /// Input files as (role, path), listed in the header.
  std::vector<std::pair<std::string, std::string>> input_files;
  /// The command that made the report (shown so it can be reproduced).
  std::string command_line;
  /// Date and time shown in the header; empty: now, UTC, ISO 8601.
  std::string generated_at;
  /// Page title.
  std::string title = "mpcal calibration report";
  /// How the page words advice (what would show more: e.g. the trajectories
  /// of a verification, Option::kVerifyTrajectories), in the caller's terms:
  /// the `mpcal` command names its flags. Empty: the page states the facts
  /// only.
  std::function<std::string(const Advice&)> explain_advice;
};

/// The whole HTML page. Never fetches anything: no external references.
std::string RenderReport(const ReportInputs& inputs);

/// Renders and writes the page atomically (no partial file on failure).
/// \throws mpcal::Error when the file cannot be written.
void WriteReport(const std::string& path, const ReportInputs& inputs);

/// The files a report is made from (empty path: section absent).
struct ReportFiles {
  std::string calibration;  ///< calibration file (JSON)
  std::string session;      ///< the recording, read with `log`
  LogOptions log;
  DetectOptions detect;
  std::string repeatability;  ///< "mpcal.repeatability/1" JSON
  std::string verification;   ///< "mpcal.verification/1" JSON
  /// Prefix of the trajectory CSVs as `mpcal verify --trajectory-csv PREFIX`
  /// writes them: PREFIX-reference.csv, PREFIX-raw.csv and (optional)
  /// PREFIX-corrected.csv. Overrides files the result names.
  std::string verification_trajectories;
  std::string noise;  ///< "mpcal.noise/1" JSON from the noise analysis

  /// Empty when valid, else names the first bad field.
  std::string Validate() const;
};

/// Reads every file named in `files` into ReportInputs (session: read and
/// static intervals detected). `input_files` is filled; the rest default.
/// \throws mpcal::Error for a missing, unreadable or malformed file (the
///   message names it), or invalid options.
ReportInputs LoadReportInputs(const ReportFiles& files);

}  // namespace mpcal
