# `make package`: a Debian package of everything `cmake --install` installs
# (the command, its man pages and bash and zsh completion, the library, its
# headers and CMake package files), made by CPack's DEB generator.
# dpkg-shlibdeps reads the binary and declares the shared libraries it links
# (Ceres, glog, fmt, GeographicLib, ...) as Depends with the versions built
# against; a program built on the library needs the -dev packages, suggested.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME mpcal)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
set(CPACK_PACKAGE_DESCRIPTION
    "mpcal calibrates MEMS inertial sensors in the field: the accelerometer by the
multi-position method (gravity's magnitude is the only reference), the
gyroscope from the turns between the positions, the noise by Allan deviation.
The package holds the mpcal command with its man pages and bash and zsh
completion, the C++ library with its headers and CMake package
(find_package(mpcal)), and the Python module mpcal (import mpcal).")
set(MPCAL_PACKAGE_CONTACT "mpcal maintainers <maintainers@users.noreply.h-seed-34f1b310.example>"
    CACHE STRING "Maintainer field of the Debian package")
set(CPACK_PACKAGE_CONTACT "${MPCAL_PACKAGE_CONTACT}")
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# The Python module (built when pybind11 was found) imports numpy; the
# command does not need it.
if(TARGET _mpcal)
  set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "python3-numpy")
endif()
set(CPACK_DEBIAN_PACKAGE_SUGGESTS
    "libeigen3-dev, libceres-dev, libgeographiclib-dev, nlohmann-json3-dev, libfmt-dev, libfast-float-dev")
# `make package_source` (which include(CPack) adds): the tracked tree as a
# tarball, without git or build folders; built from it, `mpcal --version`
# says "revision unknown".
set(CPACK_SOURCE_GENERATOR TGZ)
set(CPACK_SOURCE_IGNORE_FILES "/[.]git$" "/[.]git/" "/build[^/]*/" "/[.]cache/" "/mpcal-demo/"
    "__pycache__")
include(CPack)
