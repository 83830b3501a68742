# Manual pages made from the programs' own --help and --version by help2man (Debian's help2man), so
# the page and the program cannot drift apart. Without help2man the build goes on without them.
find_program(ROADLOAD_HELP2MAN help2man)

# roadload_man_page(TARGET SECTION SUMMARY): TARGET.SECTION beside the program, built with it and
# installed under share/man.
function(roadload_man_page target section summary)
  if(NOT ROADLOAD_HELP2MAN)
    return()
  endif()
  set(page ${CMAKE_CURRENT_BINARY_DIR}/${target}.${section})
  add_custom_command(OUTPUT ${page}
    COMMAND ${ROADLOAD_HELP2MAN} --no-info --no-discard-stderr --section ${section} --name "${summary}"
            --output ${page} $<TARGET_FILE:${target}>
    DEPENDS ${target}
    COMMENT "help2man ${target}.${section}")
  add_custom_target(${target}-man ALL DEPENDS ${page})
  install(FILES ${page} DESTINATION ${CMAKE_INSTALL_MANDIR}/man${section})
endfunction()

# roadload_subcommand_man_pages(TARGET): TARGET-COMMAND.1 for each of its subcommands, from the
# subcommand's --help (cmake/subcommand-man-pages.sh), installed beside TARGET.1.
function(roadload_subcommand_man_pages target)
  if(NOT ROADLOAD_HELP2MAN)
    return()
  endif()
  set(dir ${CMAKE_CURRENT_BINARY_DIR}/man)
  set(stamp ${dir}/.stamp)
  add_custom_command(OUTPUT ${stamp}
    COMMAND ${PROJECT_SOURCE_DIR}/cmake/subcommand-man-pages.sh ${ROADLOAD_HELP2MAN} $<TARGET_FILE:${target}> ${dir}
    COMMAND ${CMAKE_COMMAND} -E touch ${stamp}
    DEPENDS ${target} ${PROJECT_SOURCE_DIR}/cmake/subcommand-man-pages.sh
    COMMENT "help2man ${target}-*.1")
  add_custom_target(${target}-subcommand-man ALL DEPENDS ${stamp})
  install(DIRECTORY ${dir}/ DESTINATION ${CMAKE_INSTALL_MANDIR}/man1 FILES_MATCHING PATTERN "${target}-*.1")
endfunction()
