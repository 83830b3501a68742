# UndefinedBehaviorSanitizer without five of its checks: alignment, null, vptr, object-size and
# pointer-overflow instrument every pointer use, which makes Eigen-heavy code compile 35-40 % slower
# (measured: crr_filter_test.cpp 42 s -> 26 s, gap/engine.cpp 13 s -> 10 s). AddressSanitizer
# reports null dereferences and out-of-bounds accesses itself; x86-64 and arm64 tolerate misaligned
# scalars; there is little run-time polymorphism to check. The rest of UBSan (integer overflow,
# shifts, bounds of arrays, float casts, enums and bools, missing returns) stays on.
set(ROADLOAD_UBSAN_SKIP -fno-sanitize=alignment,null,vptr,object-size,pointer-overflow)
if(ROADLOAD_SANITIZE)
  add_compile_options(-fsanitize=address,undefined ${ROADLOAD_UBSAN_SKIP} -fno-omit-frame-pointer -fno-sanitize-recover=all)
  add_link_options(-fsanitize=address,undefined)
endif()
if(ROADLOAD_FUZZ)
  if(NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "ROADLOAD_FUZZ needs clang (CXX=clang++)")
  endif()
  # Library code is instrumented for coverage; the fuzzer main is linked only into fuzz targets.
  add_compile_options(-fsanitize=fuzzer-no-link,address,undefined ${ROADLOAD_UBSAN_SKIP} -fno-omit-frame-pointer)
  add_link_options(-fsanitize=address,undefined)
endif()
