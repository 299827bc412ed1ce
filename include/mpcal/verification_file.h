/// \file verification_file.h
/// \brief The files of a field verification, each read and written here:
/// the result (`"format": "mpcal.verification/1"`: VerificationToJson,
/// ParseVerificationJson) and the trajectory CSVs (`t_s,e_m,n_m,u_m[,q]`:
/// PathToCsv, ReadEastNorthCsv).
///
/// VerifyResult and TimedPath (mpcal/verify.h, mpcal/trajectory.h) are used as
/// structs only: the io room that holds these formats does not link the
/// trajectory room. The file spells the enums (time alignment, mount) in its
/// own vocabulary, fixed by the format's version.
#pragma once

#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "mpcal/trajectory.h"
#include "mpcal/verify.h"

namespace mpcal {

/// The format tag of the verification result this version writes.
inline constexpr const char* kVerificationFormat = "mpcal.verification/1";

/// A horizontal path in the local east-north frame (m) against time (s).
struct EastNorthPath {
  std::vector<double> time_s;
  std::vector<double> east_m;
  std::vector<double> north_m;
};

/// The figures of a verification result (`"format": "mpcal.verification/1"`)
/// and, when available, the paths themselves.
struct VerificationSummary {
  struct Metrics {
    double start_end_distance_m = 0.0;
    std::optional<double> horizontal_rms_m;  ///< to the reference
    std::optional<double> horizontal_max_m;
    std::optional<double> path_length_m;
  };
  Metrics reference;
  Metrics raw;
  std::optional<Metrics> corrected;  ///< only when verified with a calibration
  std::optional<EastNorthPath> reference_path;
  std::optional<EastNorthPath> raw_path;
  std::optional<EastNorthPath> corrected_path;
  /// Trajectory files named by the result, resolved against its directory
  /// (role → path); empty when it names none.
  std::vector<std::pair<std::string, std::string>> trajectory_files;
  /// How the paths were made (time alignment, mount, gyroscope, stops, ...)
  /// as (what, value) lines for the report, and the verifier's warnings.
  std::vector<std::pair<std::string, std::string>> details;
  std::vector<std::string> warnings;
};

/// The result file: `"format": "mpcal.verification/1"`, with `reference`,
/// `raw` and (with a calibration) `corrected`, plus `time_alignment` and
/// `integration` details, and `trajectories` when `trajectory_files` names
/// the paths' CSVs (role "reference", "raw" or "corrected" → path, relative
/// to the result's folder), so that `mpcal report` finds them.
/// Pretty-printed, newline-ended.
std::string VerificationToJson(
    const VerifyResult& result,
    const std::vector<std::pair<std::string, std::string>>& trajectory_files = {});

/// CSV for plotting: `t_s,e_m,n_m,u_m` per point (reference: plus `q`).
std::string PathToCsv(const TimedPath& path, const std::vector<int>& quality = {});

/// Parses the JSON text of a verification result. `origin` names the source
/// in messages and is the base for relative trajectory paths it names.
/// Trajectory files are not read here (see LoadReportInputs).
/// \throws mpcal::Error for malformed JSON, another format, or a missing or
///   wrongly-typed field.
VerificationSummary ParseVerificationJson(const std::string& text,
                                          const std::string& origin);

/// Reads the verification result at `path` (ParseVerificationJson).
/// \throws mpcal::Error (ErrorKind::kIo) for a missing or unreadable file or a
///   directory, and as ParseVerificationJson.
VerificationSummary ReadVerificationFile(const std::string& path);

/// Reads a trajectory CSV with a header naming a time column (`t`, `time`,
/// `time_s`), an east column (`e`, `east`, `east_m`) and a north column (`n`,
/// `north`, `north_m`); other columns are ignored.
/// \throws mpcal::Error when unreadable, a column is missing, or a value is
///   not a finite number (the message names the line).
EastNorthPath ReadEastNorthCsv(const std::string& path);

}  // namespace mpcal
