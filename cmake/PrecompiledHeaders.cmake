# The standard library, Eigen and GoogleTest headers make up most of each file's compile time, and
# CI has 20 minutes on 2 cores: every target parses them once, not once per file.
option(ROADLOAD_PCH "Precompile the standard library, Eigen and GoogleTest headers" ON)
find_package(Eigen3 REQUIRED NO_MODULE)

set(ROADLOAD_PCH_HEADERS
  <algorithm> <array> <cmath> <cstdint> <cstdio> <filesystem> <fstream> <map> <memory> <optional>
  <span> <sstream> <string> <string_view> <vector> <Eigen/Cholesky> <Eigen/Core>)

# roadload_precompiled_headers(target [GTEST])
function(roadload_precompiled_headers target)
  if(NOT ROADLOAD_PCH)
    return()
  endif()
  set(headers ${ROADLOAD_PCH_HEADERS})
  set(kind LIBRARY)
  if("GTEST" IN_LIST ARGN)
    list(APPEND headers <gtest/gtest.h>)
    set(kind GTEST)
  endif()
  # With position-independent code (the Python module, cmake/Python.cmake) the libraries compile
  # with -fPIC and the programs with -fPIE, and GCC refuses a header made with the other: the
  # programs get one of their own.
  get_target_property(type ${target} TYPE)
  if(CMAKE_POSITION_INDEPENDENT_CODE AND type STREQUAL "EXECUTABLE")
    set(kind ${kind}_PIE)
  endif()
  # One header per kind for the whole build, made by its first target and reused by the others:
  # the flags are the same everywhere, and the definitions that differ appear in no header of it.
  # Eigen is in the header even for targets that use none of it (the simulator, the drivers).
  target_link_libraries(${target} PRIVATE Eigen3::Eigen)
  get_property(owner GLOBAL PROPERTY ROADLOAD_PCH_OWNER_${kind})
  if(owner)
    target_precompile_headers(${target} REUSE_FROM ${owner})
  else()
    target_precompile_headers(${target} PRIVATE ${headers})
    set_property(GLOBAL PROPERTY ROADLOAD_PCH_OWNER_${kind} ${target})
  endif()
endfunction()
