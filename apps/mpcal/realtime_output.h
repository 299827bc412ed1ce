// A log written at the pace of its sensor: `simulate static --realtime`,
// so that a live session can be tried without hardware.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace mpcal::cli {

/// Writes `csv` (its header lines, then one line per element of `time_s`)
/// to `path` ("-": standard output; a file grows line by line, as a
/// logger's would) at `speed` times the pace of `time_s`: row k once
/// (time_s[k] - time_s[0]) / speed seconds have passed, lines that fall due
/// together in one write, every few milliseconds at most.
/// Returns false when the reader went away (a closed pipe: the reader of a
/// pipeline has what it wanted), true when everything was written.
/// \throws mpcal::Error when the output cannot be opened or written.
bool WriteAtSensorPace(const std::string& path,
                       std::string_view csv,
                       const std::vector<double>& time_s,
                       double speed);

}  // namespace mpcal::cli
