// One libFuzzer binary per target: the build passes the target's name as ROADLOAD_FUZZ_TARGET.
#include "targets.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  roadload::fuzz::ROADLOAD_FUZZ_TARGET(data, size);
  return 0;
}
