#include "colour.h"

#include <cstdlib>

#include <unistd.h>

#include <fmt/format.h>

namespace mpcal::cli {

bool ColourOn(std::FILE* stream) {
  // no-color.org: present and not empty turns colour off.
  const char* no_color = std::getenv("NO_COLOR");
  if (no_color != nullptr && no_color[0] != '\0') return false;
  return ::isatty(::fileno(stream)) == 1;
}

std::string Paint(std::FILE* stream, std::string_view text, Tint tint) {
  if (!ColourOn(stream)) return std::string(text);
  const char* code = tint == Tint::kGood ? "32" : tint == Tint::kLookAt ? "33" : "31";
  return fmt::format("\x1b[{}m{}\x1b[0m", code, text);
}

std::string PaintVerdict(std::FILE* stream, Verdict verdict, int width) {
  const std::string word = std::string(ToString(verdict));
  const std::string pad(
      word.size() < static_cast<std::size_t>(width) ? width - word.size() : 0, ' ');
  const Tint tint = verdict == Verdict::kGood     ? Tint::kGood
                    : verdict == Verdict::kLookAt ? Tint::kLookAt
                                                  : Tint::kDoNotUse;
  return Paint(stream, word, tint) + pad;
}

}  // namespace mpcal::cli
