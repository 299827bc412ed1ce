// Colour for a terminal: the verdict words and the `mpcal: error:` and
// `mpcal: warning:` prefixes, green for good, yellow for a look, red for do
// not use and errors. None when the stream is not a terminal or NO_COLOR is
// set (no-color.org), so that pipes, files and scripts get plain text.
#pragma once

#include <cstdio>
#include <string>
#include <string_view>

#include "mpcal/check.h"

namespace mpcal::cli {

enum class Tint { kGood, kLookAt, kDoNotUse };

/// Whether text written to `stream` is coloured.
bool ColourOn(std::FILE* stream);

/// `text` in the tint's colour when `stream` is coloured, else as it is.
std::string Paint(std::FILE* stream, std::string_view text, Tint tint);

/// The verdict's word ("good", "look at", "do not use") padded to `width`,
/// coloured for `stream`.
std::string PaintVerdict(std::FILE* stream, Verdict verdict, int width = 0);

}  // namespace mpcal::cli
