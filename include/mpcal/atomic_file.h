/// \file atomic_file.h
/// \brief Output files that appear whole or not at all.
///
/// Every file mpcal writes goes through here: the content is written to a
/// temporary file in the destination's directory and renamed over the
/// destination only on success, so an error or a crash never leaves a
/// half-written file behind. "-" means standard output.
///
/// Only regular files are replaced so. A symbolic link is followed and the
/// file it names is replaced (the link stays); a character device or a FIFO
/// (/dev/null, a named pipe) is written in place, and /dev/stdout,
/// /dev/stderr, /dev/fd/N go to the open descriptor, so that no device node
/// is ever replaced by a regular file. Block devices and sockets cannot be
/// written whole or not at all and are refused.
#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace mpcal {

/// Writes `content` to `path` atomically.
/// \throws mpcal::Error when the directory is missing or not writable, the
///   path is empty, a directory, a block device or a socket, or a write fails
///   (a full disk, /dev/full, a closed standard output).
void WriteFileAtomically(const std::string& path, const std::string& content);

/// Streams into `path` atomically: `write` gets an ostream; the file appears
/// only if `write` returns without throwing and every byte reached the disk.
/// The ostream of a file seeks (seekp), for a writer that completes a header
/// at the end; that of a pipe or a terminal fails to.
/// \throws mpcal::Error on I/O failure; rethrows what `write` throws (and
///   removes the temporary file).
void WriteStreamAtomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write);

/// Checks, before any work, that `path` can be written: not a directory, in
/// a directory that exists and is writable (a device or FIFO: writable; "-"
/// and /dev/stdout: standard output open), so that a long run does not end in an error
/// that loses its result. \throws mpcal::Error naming the path and what to do.
void CheckWritable(const std::string& path);

/// Refuses (throws mpcal::Error) when `output` names the same file as
/// `input` (same path, or the same inode through a link).
void RefuseOverwritingInput(const std::string& input, const std::string& output);

/// What a command checks of each output before it reads anything:
/// CheckWritable, then RefuseOverwritingInput against every input given
/// (empty names, options not given, are skipped).
/// \throws mpcal::Error as those two do.
void CheckOutput(const std::string& output, const std::vector<std::string>& inputs);

}  // namespace mpcal
