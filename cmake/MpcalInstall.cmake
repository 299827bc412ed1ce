# `cmake --install`: the command with its man pages and shell completion, the
# headers, the room libraries under the export set mpcal::, and a package
# config so that find_package(mpcal) works.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(_rooms)
foreach(room IN LISTS MPCAL_ROOMS)
  list(APPEND _rooms mpcal_${room})
endforeach()
install(TARGETS mpcal ${_rooms} EXPORT mpcalTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        INCLUDES DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(DIRECTORY include/mpcal DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(TARGETS mpcal_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# The man pages and the completion the build wrote (apps/mpcal/CMakeLists.txt).
install(DIRECTORY ${MPCAL_MAN_DIR}/ DESTINATION ${CMAKE_INSTALL_MANDIR}/man1
        FILES_MATCHING PATTERN "*.1")
install(FILES ${MPCAL_COMPLETION}
        DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions)
# zsh's folder depends on the prefix, known only when installing (CPack
# installs under /usr): Debian's zsh reads packages' completion from
# /usr/share/zsh/vendor-completions and the local administrator's from
# /usr/local/share/zsh/site-functions.
install(CODE "
  if(CMAKE_INSTALL_PREFIX STREQUAL \"/usr\")
    set(mpcal_zsh_dir share/zsh/vendor-completions)
  else()
    set(mpcal_zsh_dir share/zsh/site-functions)
  endif()
  file(INSTALL \"${MPCAL_ZSH_COMPLETION}\"
       DESTINATION \"\${CMAKE_INSTALL_PREFIX}/\${mpcal_zsh_dir}\")")
install(EXPORT mpcalTargets NAMESPACE mpcal::
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/mpcal)
configure_package_config_file(cmake/mpcalConfig.cmake.in
  ${CMAKE_CURRENT_BINARY_DIR}/mpcalConfig.cmake
  INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/mpcal)
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/mpcalConfigVersion.cmake
  COMPATIBILITY SameMajorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/mpcalConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/mpcalConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/mpcal)
