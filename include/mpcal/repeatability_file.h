/// \file repeatability_file.h
/// \brief The repeatability table's files: the JSON (`"format":
/// "mpcal.repeatability/1"`, written and read back) and the CSV (written).
///
/// The table itself is RepeatabilityResult (mpcal/repeat.h); only its struct is
/// used here, so the io room that reads and writes the files does not link the
/// statistics.
#pragma once

#include <string>

#include "mpcal/repeat.h"

namespace mpcal {

/// The format tag of the repeatability JSON this version writes.
inline constexpr const char* kRepeatabilityFormat = "mpcal.repeatability/1";

/// The JSON of the issue (`"format": "mpcal.repeatability/1"`), SI units,
/// pretty-printed and newline-ended:
/// {"format", "trials", "parameters": {"bias_mps2": {"values": [[x,y,z],...],
/// "mean", "std_population", "std_sample", "changed": [bool|null ×3]},
/// "scale_factor_error": {...}, "non_orthogonality_rad": {"yz": {"values":
/// [...], "mean", ...}, "zx": {...}, "zy": {...}}}}.
std::string RepeatabilityToJson(const RepeatabilityResult& result);

/// Parses the JSON written by RepeatabilityToJson. `origin` names the source
/// in messages (a path). Fields the file does not hold (names, conditions,
/// χ², p-values) are left at their defaults; names become "trial 1", ...
/// \throws mpcal::Error for malformed JSON, a missing or wrongly-typed field,
///   an unknown format or major version, arrays whose length disagrees with
///   "trials", or a non-finite value.
RepeatabilityResult RepeatabilityFromJson(const std::string& text,
                                          const std::string& origin);

/// Reads the repeatability JSON at `path` (RepeatabilityFromJson).
/// \throws mpcal::Error (ErrorKind::kIo) for a missing or unreadable file or a
///   directory, and as RepeatabilityFromJson.
RepeatabilityResult ReadRepeatabilityFile(const std::string& path);

/// The table as CSV, SI units, one row per parameter:
/// `parameter,trial_1,...,trial_n,mean,std_population,std_sample,changed,chi2,p_value`
/// (parameter names of kParameterNames; `changed` is true/false or empty
/// without a verdict; chi2 and p_value empty when absent).
std::string RepeatabilityToCsv(const RepeatabilityResult& result);

}  // namespace mpcal
