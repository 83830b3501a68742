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
