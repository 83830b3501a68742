# The standard library, Eigen and GoogleTest headers make up most of each file's compile time, and
# CI has 20 minutes on 2 cores: every target parses them once, not once per file.
option(ROADLOAD_PCH "Precompile the standard library, Eigen and GoogleTest headers" ON)

set(ROADLOAD_PCH_HEADERS
  <algorithm> <array> <cmath> <cstdint> <cstdio> <filesystem> <fstream> <map> <memory> <optional>
  <span> <sstream> <string> <string_view> <vector> <Eigen/Cholesky> <Eigen/Core>)

# roadload_precompiled_headers(target [GTEST])
function(roadload_precompiled_headers target)
  if(NOT ROADLOAD_PCH)
    return()
  endif()
  set(headers ${ROADLOAD_PCH_HEADERS})
  if("GTEST" IN_LIST ARGN)
    list(APPEND headers <gtest/gtest.h>)
  endif()
  target_precompile_headers(${target} PRIVATE ${headers})
endfunction()
