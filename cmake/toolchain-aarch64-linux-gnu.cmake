# Cross build for 64-bit ARM (the truck's board) with Debian's cross toolchain and multiarch
# libraries: g++-aarch64-linux-gnu, and the arm64 -dev packages installed beside the amd64 ones
# (dpkg --add-architecture arm64; scripts/cross-arm64 installs them). Tests run under qemu-user.
#
#   cmake -S . -B build-arm64 -DCMAKE_TOOLCHAIN_FILE=cmake/toolchain-aarch64-linux-gnu.cmake
set(CMAKE_SYSTEM_NAME Linux)
set(CMAKE_SYSTEM_PROCESSOR aarch64)
set(ROADLOAD_CROSS_TRIPLE aarch64-linux-gnu)

set(CMAKE_C_COMPILER ${ROADLOAD_CROSS_TRIPLE}-gcc)
set(CMAKE_CXX_COMPILER ${ROADLOAD_CROSS_TRIPLE}-g++)

# Debian multiarch: arm64 libraries live in /usr/lib/aarch64-linux-gnu and their CMake packages in
# /usr/lib/aarch64-linux-gnu/cmake; headers are the arch-independent ones in /usr/include, which
# the cross compiler searches after its own libc and libstdc++ headers. The library architecture
# makes find_library and find_package look in the aarch64 folders and never in x86_64-linux-gnu.
# The root is the host's own "/"; programs (python3, the UML scripts) are the host's.
set(CMAKE_LIBRARY_ARCHITECTURE ${ROADLOAD_CROSS_TRIPLE})
set(CMAKE_FIND_ROOT_PATH /)
set(CMAKE_FIND_ROOT_PATH_MODE_PROGRAM NEVER)
set(CMAKE_FIND_ROOT_PATH_MODE_LIBRARY ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_INCLUDE ONLY)
set(CMAKE_FIND_ROOT_PATH_MODE_PACKAGE ONLY)

# pkg-config: pkgconf:arm64 (pulled in by the arm64 -dev packages) ships the triplet wrapper,
# which reads only the arm64 .pc files. The variables below do the same for a plain pkg-config.
if(EXISTS /usr/bin/${ROADLOAD_CROSS_TRIPLE}-pkg-config)
  set(PKG_CONFIG_EXECUTABLE /usr/bin/${ROADLOAD_CROSS_TRIPLE}-pkg-config CACHE FILEPATH "pkg-config for arm64")
endif()
set(ENV{PKG_CONFIG_LIBDIR} /usr/lib/${ROADLOAD_CROSS_TRIPLE}/pkgconfig:/usr/share/pkgconfig)

# GeographicLib: Debian's libgeographiclib-dev is not Multi-Arch: same, so its arm64 build cannot
# be installed beside the amd64 one the native builds need. Its headers are identical on both
# (checked for 2.1.2-1), so the amd64 -dev package provides them and libgeographiclib23:arm64 the
# library; FindGeographicLib finds only the unversioned libGeographicLib.so, so point it at the
# versioned arm64 one (it derives the include folder, /usr/include, from this path).
if(NOT GeographicLib_LIBRARIES)
  file(GLOB _roadload_geographiclib /usr/lib/${ROADLOAD_CROSS_TRIPLE}/libGeographicLib.so.[0-9]*)
  list(SORT _roadload_geographiclib)
  list(LENGTH _roadload_geographiclib _roadload_n)
  if(_roadload_n GREATER 0)
    list(GET _roadload_geographiclib 0 _roadload_geographiclib)
    set(GeographicLib_LIBRARIES ${_roadload_geographiclib} CACHE FILEPATH "arm64 GeographicLib")
  endif()
  unset(_roadload_geographiclib)
  unset(_roadload_n)
endif()

# Test binaries run on the host through qemu-user: gtest_discover_tests lists them at build time,
# ctest runs them. The arm64 loader and libraries come from the multiarch packages (libc6:arm64
# puts /lib/ld-linux-aarch64.so.1 in place), so qemu needs no -L.
find_program(ROADLOAD_QEMU_AARCH64 NAMES qemu-aarch64 qemu-aarch64-static)
if(ROADLOAD_QEMU_AARCH64)
  set(CMAKE_CROSSCOMPILING_EMULATOR ${ROADLOAD_QEMU_AARCH64})
endif()
