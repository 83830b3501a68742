# The Debian package (`scripts/package`, or `cpack -G DEB` in a build folder): CPack's DEB
# generator packs what `cmake --install` installs, so the package and an install from source
# cannot differ. A package is built from a /usr prefix (Debian policy; /etc and /var follow from
# it, scripts/build configures it), and dpkg-shlibdeps finds the libraries' packages for Depends.
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME roadload)
set(CPACK_PACKAGE_VENDOR roadload)
set(CPACK_PACKAGE_CONTACT "roadload maintainers <roadload@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "truck rolling-resistance logger and estimator, pavement by pavement")
# CPack puts the summary first; this is the long description under it.
set(CPACK_PACKAGE_DESCRIPTION
    "roadloadd records J1939 over SocketCAN, SPI accelerometers and gpsd's GNSS on one capture clock and estimates \
the rolling-resistance coefficient live. roadload decodes, analyses, simulates and reports the recordings, and \
diagnoses where a drive and its simulation differ.")
# Debian ships stripped programs; the build folder keeps the line tables for backtraces.
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_PRIORITY optional)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
# The maintainer scripts call systemd-sysusers, systemd-tmpfiles and deb-systemd-helper.
# libpq5: loaded when a PostgreSQL database is opened, so dpkg-shlibdeps does not see it.
set(CPACK_DEBIAN_PACKAGE_DEPENDS "systemd, init-system-helpers, libpq5")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "gpsd, can-utils, logrotate")
# flac -d and zstdcat read the recordings' accelerometer and other streams without roadload.
set(CPACK_DEBIAN_PACKAGE_SUGGESTS "flac, zstd")
# The Python module (docs/python.md) is for Debian's python3 with its pandas, and `roadload batch`
# runs on its python3-distributed; the programs need none of them, so they are recommended.
if(ROADLOAD_PYTHON)
  string(APPEND CPACK_DEBIAN_PACKAGE_RECOMMENDS ", python3 (>= 3.11), python3 (<< 3.12), python3-pandas, python3-distributed")
endif()
set(CPACK_DEBIAN_PACKAGE_CONTROL_STRICT_PERMISSION ON)
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA
    ${PROJECT_SOURCE_DIR}/cmake/debian/conffiles ${PROJECT_SOURCE_DIR}/cmake/debian/postinst
    ${PROJECT_SOURCE_DIR}/cmake/debian/prerm ${PROJECT_SOURCE_DIR}/cmake/debian/postrm)
set(CPACK_PACKAGING_INSTALL_PREFIX ${CMAKE_INSTALL_PREFIX})
include(CPack)
