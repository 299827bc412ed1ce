# `mpcal --version` names the release and the revision it was built from.
#   cmake -DMPCAL=<binary> -DVERSION=<PROJECT_VERSION> -DSOURCE_DIR=<checkout>
#         -DSCRATCH=<dir> -P version_revision.cmake
# The revision is asked of git here, apart from cmake/MpcalGitRevision.cmake;
# that script is then run on a folder that is not the top of a checkout,
# where it must say "unknown".
# A source tree inside some other checkout (a tarball unpacked there) is not
# that checkout's revision: "unknown" too.
execute_process(COMMAND git rev-parse --show-toplevel
  WORKING_DIRECTORY ${SOURCE_DIR}
  OUTPUT_VARIABLE toplevel OUTPUT_STRIP_TRAILING_WHITESPACE
  RESULT_VARIABLE not_git ERROR_QUIET)
execute_process(COMMAND git describe --always --dirty
  WORKING_DIRECTORY ${SOURCE_DIR}
  OUTPUT_VARIABLE revision OUTPUT_STRIP_TRAILING_WHITESPACE
  RESULT_VARIABLE describe_failed ERROR_QUIET)
if(NOT not_git)
  file(REAL_PATH "${toplevel}" toplevel)
  file(REAL_PATH "${SOURCE_DIR}" source_real)
endif()
if(not_git OR describe_failed OR NOT toplevel STREQUAL source_real)
  set(revision unknown)
endif()
execute_process(COMMAND ${MPCAL} --version
  OUTPUT_VARIABLE printed OUTPUT_STRIP_TRAILING_WHITESPACE
  RESULT_VARIABLE code)
set(expected "mpcal ${VERSION} (revision ${revision})")
if(NOT code EQUAL 0 OR NOT printed STREQUAL expected)
  message(FATAL_ERROR "mpcal --version printed '${printed}' (exit ${code}), expected '${expected}'")
endif()

file(REMOVE_RECURSE ${SCRATCH})
file(MAKE_DIRECTORY ${SCRATCH}/unpacked)
execute_process(COMMAND ${CMAKE_COMMAND} -DSOURCE_DIR=${SCRATCH}/unpacked
  -DOUTPUT=${SCRATCH}/revision.h -P ${SOURCE_DIR}/cmake/MpcalGitRevision.cmake
  RESULT_VARIABLE code)
file(READ ${SCRATCH}/revision.h header)
if(NOT code EQUAL 0 OR NOT header MATCHES "#define MPCAL_GIT_REVISION \"unknown\"")
  message(FATAL_ERROR "outside a checkout's top the revision header reads: ${header}")
endif()
message(STATUS "${printed}")
