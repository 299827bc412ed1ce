#include "io/result_text.h"

#include <unistd.h>

#include <filesystem>
#include <string_view>
#include <system_error>

#include <fmt/format.h>

#include "mpcal/error.h"
#include "mpcal/text_input.h"

namespace mpcal::internal {

std::string ReadResultText(const std::string& path, const char* what) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) {
    throw Error(ErrorKind::kIo,
                fmt::format("{}: is a directory, expected {}", path, what));
  }
  if (::access(path.c_str(), R_OK) != 0) {
    throw Error(ErrorKind::kIo,
                fmt::format("{}: cannot open {} (does it exist?)", path, what));
  }
  std::string_view kind(what);
  if (kind.starts_with("a ")) kind.remove_prefix(2);
  return ReadTextInput(
      path, kind.ends_with("CSV") ? kMaxReferenceFileBytes : kMaxResultFileBytes, kind);
}

}  // namespace mpcal::internal
