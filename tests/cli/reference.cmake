# The version, and the reference the build writes from the flag table: the
# man pages and the bash completion (apps/mpcal/reference.cc).
add_test(NAME cli.version_names_revision
  COMMAND ${CMAKE_COMMAND} -DMPCAL=$<TARGET_FILE:mpcal_cli> -DVERSION=${PROJECT_VERSION}
          -DSOURCE_DIR=${PROJECT_SOURCE_DIR} -DSCRATCH=${CMAKE_CURRENT_BINARY_DIR}/version
          -P ${CMAKE_CURRENT_SOURCE_DIR}/version_revision.cmake)
add_test(NAME cli.man_pages
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/man_pages.sh $<TARGET_FILE:mpcal_cli> ${MPCAL_MAN_DIR})
add_test(NAME cli.bash_completion
  COMMAND bash ${CMAKE_CURRENT_SOURCE_DIR}/completion.sh $<TARGET_FILE:mpcal_cli>
          ${MPCAL_COMPLETION})
# zsh is not needed to build or use mpcal: without it the check is skipped.
find_program(MPCAL_ZSH zsh)
if(MPCAL_ZSH)
  add_test(NAME cli.zsh_completion
    COMMAND ${MPCAL_ZSH} -f ${CMAKE_CURRENT_SOURCE_DIR}/completion_zsh.zsh
            $<TARGET_FILE:mpcal_cli> ${MPCAL_ZSH_COMPLETION})
  set_tests_properties(cli.zsh_completion PROPERTIES LABELS cli)
endif()
mpcal_cli_test(generate_unknown EXIT 2 MATCH "mpcal: error: --generate: give 'man DIRECTORY'"
  ARGS --generate html)
mpcal_cli_test(generate_missing_dir EXIT 1 MATCH "mpcal: error: .*no-such-dir"
  ARGS --generate man no-such-dir)
set_tests_properties(cli.version_names_revision cli.man_pages cli.bash_completion
  PROPERTIES LABELS cli)
