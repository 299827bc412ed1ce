// Reading a results file (a repeatability table, a verification result, a
// trajectory CSV) whole, with the messages the report has always given for a
// missing file or a directory. Private to the io room.
#pragma once

#include <string>

namespace mpcal::internal {

/// All of `path`; `what` names the kind of file ("a verification result";
/// "... CSV" allows the larger size of a reference).
/// \throws mpcal::Error (kIo) for a directory, a file that cannot be opened,
///   or what ReadTextInput refuses.
std::string ReadResultText(const std::string& path, const char* what);

}  // namespace mpcal::internal
