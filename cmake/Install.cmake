# Where an installed roadload keeps its files (GNUInstallDirs, so a Debian prefix of /usr puts the
# configuration under /etc and the state under /var). The programs find the data folder relative
# to their own at run time (drivers/src/definitions.cpp); nothing installed names the source tree.
include(GNUInstallDirs)
set(ROADLOAD_INSTALL_DATADIR ${CMAKE_INSTALL_DATADIR}/roadload)
set(ROADLOAD_INSTALL_FULL_DATADIR ${CMAKE_INSTALL_FULL_DATADIR}/roadload)
set(ROADLOAD_INSTALL_FULL_CONFDIR ${CMAKE_INSTALL_FULL_SYSCONFDIR}/roadload)

# systemd's own folders for units, sysusers and tmpfiles, as its pkg-config file names them for a
# /usr prefix; under any other prefix the same layout below it.
find_package(PkgConfig REQUIRED)
function(roadload_systemd_dir out variable fallback)
  if(CMAKE_INSTALL_PREFIX STREQUAL "/usr")
    pkg_get_variable(dir systemd ${variable})
  endif()
  if(NOT dir)
    set(dir ${CMAKE_INSTALL_PREFIX}/${fallback})
  endif()
  set(${out} ${dir} PARENT_SCOPE)
endfunction()
roadload_systemd_dir(ROADLOAD_UNIT_DIR systemdsystemunitdir lib/systemd/system)
roadload_systemd_dir(ROADLOAD_SYSUSERS_DIR sysusersdir lib/sysusers.d)
roadload_systemd_dir(ROADLOAD_TMPFILES_DIR tmpfilesdir lib/tmpfiles.d)
if(CMAKE_INSTALL_PREFIX STREQUAL "/usr")
  set(ROADLOAD_UDEV_RULES_DIR /lib/udev/rules.d)
else()
  set(ROADLOAD_UDEV_RULES_DIR ${CMAKE_INSTALL_PREFIX}/lib/udev/rules.d)
endif()

# The data every command reads: J1939 definitions, routes, scenarios, vehicles and the gap bench's
# test days. The daemon's example settings are the package's configuration file.
function(roadload_install_data)
  install(FILES ${PROJECT_SOURCE_DIR}/config/j1939-core.dbc DESTINATION ${ROADLOAD_INSTALL_DATADIR})
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/config/routes ${PROJECT_SOURCE_DIR}/config/scenarios
                    ${PROJECT_SOURCE_DIR}/config/vehicles ${PROJECT_SOURCE_DIR}/config/bench
          DESTINATION ${ROADLOAD_INSTALL_DATADIR})
  install(FILES ${PROJECT_SOURCE_DIR}/config/roadloadd.toml DESTINATION ${ROADLOAD_INSTALL_FULL_CONFDIR})
  install(FILES ${PROJECT_SOURCE_DIR}/README.md DESTINATION ${CMAKE_INSTALL_DOCDIR})
  # A real truck's J1939 trace (MIT, with its licence) to try `roadload decode` on.
  set(traces ${PROJECT_SOURCE_DIR}/tests/data/traces)
  install(FILES ${traces}/css-fcbf0606-tp-sample.log ${traces}/LICENSE-css-electronics-api-examples
          DESTINATION ${CMAKE_INSTALL_DOCDIR}/examples)
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR} FILES_MATCHING PATTERN "*.md"
          PATTERN "journal.md" EXCLUDE)
endfunction()
