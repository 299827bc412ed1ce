// The facts of `export` and `import` in words: what a file could not carry.
#pragma once

#include <string>
#include <vector>

#include "mpcal/export.h"

namespace mpcal::cli {

/// One line per note, naming `file` (the written or read file).
std::string DescribeExportNote(const ExportNote& note, const std::string& file);

/// The registry's names, for the help and the choices of FORMAT: those that
/// write (`writing`) or read.
std::vector<std::string> ExportFormatNames(bool writing);

/// "  kalibr    Kalibr imu.yaml (needs ...)" lines for a command's footer.
std::string FormatList(bool writing);

}  // namespace mpcal::cli
