# Ceres (a static library on Debian) names its dependencies as shared
# libraries: glog, gflags, SuiteSparse, CXSparse, LAPACK and BLAS (ATLAS,
# compiled Fortran, with the Fortran, quadmath and OpenMP runtimes under
# them). mpcal's fits are small and dense (Eigen inside Ceres), so no sparse
# or LAPACK code of theirs runs, yet every mpcal process would load and
# relocate all of them at start: 1.7 MB of the Xsens calibration's peak
# memory (bench/speed_bench.sh). Linked from their static archives instead,
# only the objects Ceres refers to are copied in and nothing of them is
# loaded. Where an archive is missing the shared libraries stay, all of them;
# so they do in the sanitizer and fuzzing builds, which test the code, not
# its footprint.
option(MPCAL_STATIC_SOLVER_DEPS
       "Link Ceres's dependencies (glog, SuiteSparse, LAPACK, BLAS) and the libraries of
       the bag readers, the Kalibr writer and the gravity model (zstd, lz4, bz2, SQLite,
       yaml-cpp, GeographicLib) from static archives"
       ON)

# The library to link for `name` (e.g. zstd): its static archive when
# MPCAL_STATIC_SOLVER_DEPS holds and the archive exists, else the shared
# library; in `out`. Like Ceres's dependencies, the libraries of the bag
# readers, the Kalibr writer and the gravity model would be loaded and
# relocated by every mpcal process although most commands never run them
# (1.3 MB of a calibration's peak memory).
function(mpcal_find_library out name)
  set(names ${name})
  if(MPCAL_STATIC_SOLVER_DEPS AND NOT MPCAL_SANITIZE AND NOT MPCAL_FUZZ)
    set(names ${CMAKE_STATIC_LIBRARY_PREFIX}${name}${CMAKE_STATIC_LIBRARY_SUFFIX} ${name})
  endif()
  find_library(MPCAL_${name}_LIBRARY NAMES ${names} REQUIRED)
  set(${out} ${MPCAL_${name}_LIBRARY} PARENT_SCOPE)
endfunction()

# The static archive beside a shared library path (lib/libx.so[.N...]), or
# NONE when there is none.
function(_mpcal_archive_of path out)
  set(archive NONE)
  if(path MATCHES "^(.*)\\.so(\\.[0-9.]+)?$")
    set(candidate "${CMAKE_MATCH_1}.a")
    if(EXISTS "${candidate}")
      set(archive "${candidate}")
    endif()
  endif()
  set(${out} "${archive}" PARENT_SCOPE)
endfunction()

# Walks `item` (a target, a genex-wrapped target or a library path) and the
# targets it links, collecting each shared library in _MPCAL_SHARED and its
# archive in _MPCAL_ARCHIVES (NONE for none), and the targets in _MPCAL_TARGETS.
function(_mpcal_collect item)
  if(item MATCHES "^\\$<LINK_ONLY:(.*)>$")
    set(item "${CMAKE_MATCH_1}")
  endif()
  if(TARGET "${item}")
    get_target_property(aliased "${item}" ALIASED_TARGET)
    if(aliased)
      set(item "${aliased}")
    endif()
    if("${item}" IN_LIST _MPCAL_TARGETS)
      return()
    endif()
    set(_MPCAL_TARGETS ${_MPCAL_TARGETS} "${item}" CACHE INTERNAL "")
    get_target_property(imported "${item}" IMPORTED)
    if(imported)
      foreach(property IMPORTED_LOCATION IMPORTED_LOCATION_RELEASE)
        get_target_property(location "${item}" ${property})
        if(location AND location MATCHES "\\.so")
          _mpcal_collect("${location}")
        endif()
      endforeach()
    endif()
    get_target_property(links "${item}" INTERFACE_LINK_LIBRARIES)
    if(links)
      foreach(link IN LISTS links)
        _mpcal_collect("${link}")
      endforeach()
    endif()
  elseif(item MATCHES "\\.so(\\.[0-9.]+)?$" AND NOT "${item}" IN_LIST _MPCAL_SHARED)
    _mpcal_archive_of("${item}" archive)
    set(_MPCAL_SHARED ${_MPCAL_SHARED} "${item}" CACHE INTERNAL "")
    set(_MPCAL_ARCHIVES ${_MPCAL_ARCHIVES} "${archive}" CACHE INTERNAL "")
  endif()
endfunction()

function(mpcal_link_solver_deps_statically)
  if(NOT MPCAL_STATIC_SOLVER_DEPS OR MPCAL_SANITIZE OR MPCAL_FUZZ OR NOT TARGET Ceres::ceres)
    return()
  endif()
  set(_MPCAL_TARGETS "" CACHE INTERNAL "")
  set(_MPCAL_SHARED "" CACHE INTERNAL "")
  set(_MPCAL_ARCHIVES "" CACHE INTERNAL "")
  _mpcal_collect(Ceres::ceres)
  # The runtimes of the Fortran LAPACK and of SuiteSparse's OpenMP, and the
  # shared libraries that have no archive but are wanted all the same.
  set(runtimes "")
  foreach(name libgfortran.a libquadmath.a libgomp.a)
    execute_process(COMMAND ${CMAKE_CXX_COMPILER} -print-file-name=${name}
                    OUTPUT_VARIABLE runtime OUTPUT_STRIP_TRAILING_WHITESPACE)
    if(NOT IS_ABSOLUTE "${runtime}" OR NOT EXISTS "${runtime}")
      message(STATUS "mpcal: Ceres's dependencies stay shared (no ${name})")
      return()
    endif()
    list(APPEND runtimes "${runtime}")
  endforeach()
  set(kept_shared "")
  set(archives "")
  foreach(shared archive IN ZIP_LISTS _MPCAL_SHARED _MPCAL_ARCHIVES)
    if(NOT archive STREQUAL "NONE")
      list(APPEND archives "${archive}")
    elseif(shared MATCHES "libmetis")
      # No archive in Debian: METIS stays shared (cholmod's partitioning).
      list(APPEND kept_shared "${shared}")
    else()
      message(STATUS "mpcal: Ceres's dependencies stay shared (no archive of ${shared})")
      return()
    endif()
  endforeach()

  foreach(target IN LISTS _MPCAL_TARGETS)
    get_target_property(imported "${target}" IMPORTED)
    if(NOT imported)
      continue()
    endif()
    foreach(property IMPORTED_LOCATION IMPORTED_LOCATION_RELEASE)
      get_target_property(location "${target}" ${property})
      if(location AND location MATCHES "\\.so")
        _mpcal_archive_of("${location}" archive)
        set_target_properties("${target}" PROPERTIES ${property} "${archive}")
      endif()
    endforeach()
    get_target_property(links "${target}" INTERFACE_LINK_LIBRARIES)
    if(links)
      set(rewritten "")
      foreach(link IN LISTS links)
        if(link MATCHES "\\.so(\\.[0-9.]+)?$" AND NOT link MATCHES "libmetis")
          _mpcal_archive_of("${link}" link)
        endif()
        list(APPEND rewritten "${link}")
      endforeach()
      set_target_properties("${target}" PROPERTIES INTERFACE_LINK_LIBRARIES "${rewritten}")
    endif()
  endforeach()
  # The archives refer to one another (LAPACK to BLAS to ATLAS, glog to
  # libunwind): all of them once more at the end, then the runtimes.
  # What the shared libraries brought with them: METIS (cholmod's
  # partitioning; Debian has no archive of it) and libunwind (glog's).
  set(tail ${archives} ${runtimes} ${kept_shared})
  find_library(MPCAL_METIS_LIBRARY NAMES metis libmetis.so.5)
  find_library(MPCAL_UNWIND_LIBRARY unwind)
  foreach(library MPCAL_METIS_LIBRARY MPCAL_UNWIND_LIBRARY)
    if(${library})
      list(APPEND tail "${${library}}")
    endif()
  endforeach()
  list(APPEND tail Threads::Threads ${CMAKE_DL_LIBS})
  set_property(TARGET Ceres::ceres APPEND PROPERTY INTERFACE_LINK_LIBRARIES ${tail})
  list(LENGTH archives count)
  message(STATUS "mpcal: Ceres's dependencies linked from ${count} static archives")
endfunction()
