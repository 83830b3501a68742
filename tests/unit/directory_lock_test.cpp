// One daemon per data directory: the lock is held while its holder lives and freed with it.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <optional>

#include "roadload/io/directory_lock.hpp"

namespace roadload::io {
namespace {

namespace fs = std::filesystem;

TEST(DirectoryLock, ASecondHolderIsRefusedUntilTheFirstLetsGo) {
  const fs::path dir = fs::temp_directory_path() / ("roadload-lock-" + std::to_string(::getpid())) / "data";
  fs::remove_all(dir.parent_path());
  std::optional<DirectoryLock> first;
  {
    auto taken = DirectoryLock::take(dir.string());
    ASSERT_TRUE(taken) << taken.error().to_string();
    first.emplace(std::move(taken.value()));
  }
  EXPECT_TRUE(fs::is_directory(dir)) << "created when missing";
  auto second = DirectoryLock::take(dir.string());
  ASSERT_FALSE(second);
  EXPECT_NE(second.error().message.find("pid " + std::to_string(::getpid())), std::string::npos) << second.error().to_string();
  EXPECT_NE(second.error().file.find(".roadloadd.lock"), std::string::npos);
  first.reset();
  EXPECT_TRUE(DirectoryLock::take(dir.string())) << "free again once the holder is gone";
  fs::remove_all(dir.parent_path());
}

TEST(DirectoryLock, ADataDirectoryThatIsAFileIsNamed) {
  const fs::path file = fs::temp_directory_path() / ("roadload-lock-file-" + std::to_string(::getpid()));
  {
    std::FILE* f = std::fopen(file.c_str(), "w");
    std::fclose(f);
  }
  auto taken = DirectoryLock::take(file.string());
  ASSERT_FALSE(taken);
  EXPECT_NE(taken.error().file.find(file.filename().string()), std::string::npos) << taken.error().to_string();
  fs::remove(file);
}

}  // namespace
}  // namespace roadload::io
