#include "version.h"

// Written at every build by cmake/MpcalGitRevision.cmake; only this file
// includes it, so a new revision recompiles one file.
#include "mpcal_git_revision.h"

namespace mpcal::cli {

std::string VersionLine() {
  return std::string("mpcal ") + MPCAL_VERSION + " (revision " + MPCAL_GIT_REVISION + ")";
}

}  // namespace mpcal::cli
