/// \file text_input.h
/// \brief Reading a small text file whole, with the checks a log gets first.
///
/// mpcal's JSON files (calibration, repeatability, verification) and the GNSS
/// references are read whole into memory. Before reading to the end, this
/// looks at what the path is and at the first bytes, so that /dev/zero,
/// /dev/urandom or a video file named by mistake is refused at once instead
/// of filling memory.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>

namespace mpcal {

/// The most a calibration file may hold: a few kilobytes are written, a few
/// megabytes leave room for comments and a long provenance.
inline constexpr std::size_t kMaxCalibrationFileBytes = std::size_t{4} << 20;
/// The most a GNSS reference or a trajectory CSV may hold: a day of 10 Hz
/// RTKLIB positions is about 120 MB.
inline constexpr std::size_t kMaxReferenceFileBytes = std::size_t{512} << 20;
/// The most another mpcal JSON file (repeatability, verification) may hold.
inline constexpr std::size_t kMaxResultFileBytes = std::size_t{64} << 20;

/// Reads all of `path` ("-": standard input), which must be a regular file
/// or a pipe of at most `max_bytes` whose first bytes are text. `what` names
/// the kind of file in messages ("calibration file").
/// \throws mpcal::Error naming `path`: missing or unreadable, a directory, a
///   device or socket, larger than `max_bytes` (checked before reading a
///   regular file, and as a pipe is read), NUL bytes or many control
///   characters in the first 64 KiB, or a read error.
std::string ReadTextInput(const std::string& path,
                          std::size_t max_bytes,
                          std::string_view what);

}  // namespace mpcal
