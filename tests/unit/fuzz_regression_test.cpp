// Every seed and every crasher the fuzzers ever found, replayed through the fuzz bodies in
// ordinary builds, so a fixed crash stays fixed.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <vector>

#include "../fuzz/targets.hpp"

namespace {

namespace fs = std::filesystem;

std::size_t replay(const roadload::fuzz::Target& target, const fs::path& dir) {
  if (!fs::exists(dir)) return 0;
  std::size_t n = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    std::ifstream in(entry.path(), std::ios::binary);
    const std::vector<char> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    target.run(reinterpret_cast<const std::uint8_t*>(bytes.data()), bytes.size());
    ++n;
  }
  return n;
}

TEST(FuzzRegression, EverySeedAndCrasherRunsCleanly) {
  const fs::path root = fs::path(ROADLOAD_TEST_DATA).parent_path() / "fuzz";
  for (const auto& target : roadload::fuzz::kTargets) {
    const std::size_t seeds = replay(target, root / "corpus" / target.name);
    replay(target, root / "regressions" / target.name);
    EXPECT_GT(seeds, 0u) << "no seed corpus for " << target.name;
  }
}

}  // namespace
