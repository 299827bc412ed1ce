// What `mpcal --version` prints: the release and the revision it was built
// from.
#pragma once

#include <string>

namespace mpcal::cli {

/// "mpcal 0.1.0 (revision 649f341-dirty)": CMake's PROJECT_VERSION and
/// `git describe --always --dirty` of the checkout at build time, or
/// "revision unknown" for a build outside git (a release tarball).
std::string VersionLine();

}  // namespace mpcal::cli
