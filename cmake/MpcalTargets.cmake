# Helpers that give every mpcal target the same settings.

# Warnings on our own targets only; -Werror behind MPCAL_WARNINGS_AS_ERRORS.
add_library(mpcal_warnings INTERFACE)
target_compile_options(mpcal_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wcast-align
  -Wunused -Woverloaded-virtual -Wnull-dereference -Wimplicit-fallthrough
  $<$<BOOL:${MPCAL_WARNINGS_AS_ERRORS}>:-Werror>)
# Each function and object in a section of its own, so that the command's
# link drops what it does not call (the library's functions for other
# callers): a smaller executable whose pages a short run touches fewer of
# (the Xsens calibration's peak memory, bench/speed_bench.sh).
if(NOT MPCAL_SANITIZE)
  target_compile_options(mpcal_warnings INTERFACE -ffunction-sections -fdata-sections)
endif()
if(MPCAL_SANITIZE)
  target_compile_options(mpcal_warnings INTERFACE
    -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=all
    # GCC 12 false positive on std::string assignment under ASan (GCC PR 105651).
    $<$<CXX_COMPILER_ID:GNU>:-Wno-restrict>)
  target_link_options(mpcal_warnings INTERFACE -fsanitize=address,undefined)
  # Under ASan Eigen stops trusting malloc's 16-byte alignment and frees with
  # its own offset scheme; Debian's Ceres (no ASan) allocates with plain
  # malloc, so a matrix made in Ceres and freed in our code would be freed
  # wrongly. Keep Eigen's allocator the same on both sides.
  target_compile_definitions(mpcal_warnings INTERFACE EIGEN_MALLOC_ALREADY_ALIGNED=1)
endif()

# mpcal_room(NAME SOURCES a.cc b.cc [PUBLIC deps...] [PRIVATE deps...])
# A room of the library: static library mpcal_NAME over the public headers.
function(mpcal_room name)
  cmake_parse_arguments(ROOM "" "" "SOURCES;PUBLIC;PRIVATE" ${ARGN})
  add_library(mpcal_${name} STATIC ${ROOM_SOURCES})
  target_include_directories(mpcal_${name}
    PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
           $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>
    PRIVATE ${PROJECT_SOURCE_DIR}/src)
  target_compile_features(mpcal_${name} PUBLIC cxx_std_20)
  set_target_properties(mpcal_${name} PROPERTIES POSITION_INDEPENDENT_CODE ON
    UNITY_BUILD ${MPCAL_UNITY_BUILD})
  target_link_libraries(mpcal_${name}
    PUBLIC Eigen3::Eigen ${ROOM_PUBLIC}
    PRIVATE $<BUILD_INTERFACE:mpcal_warnings> ${ROOM_PRIVATE})
endfunction()
