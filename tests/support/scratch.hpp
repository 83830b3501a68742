#pragma once
// Scratch files and folders of one test process, removed when it ends, so that test runs leave
// nothing in the temporary folder (under ctest each GoogleTest case is a process of its own, and
// a file per process added up to hundreds a run). A test that crashes leaves its files to look at.
#include <unistd.h>

#include <filesystem>
#include <string>
#include <system_error>
#include <vector>

namespace roadload::test {

class Scratch {
 public:
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
  ~Scratch() {
    for (const auto& p : paths_) {
      std::error_code ec;
      std::filesystem::remove_all(p, ec);
    }
  }
  static Scratch& process() {
    static Scratch s;
    return s;
  }
  const std::filesystem::path& add(std::filesystem::path p) { return paths_.emplace_back(std::move(p)); }

 private:
  Scratch() = default;
  std::vector<std::filesystem::path> paths_;
};

// TMPDIR/NAME-PID then SUFFIX, removed with all under it when the process ends.
inline std::filesystem::path scratch_path(const std::string& name, const std::string& suffix = "") {
  return Scratch::process().add(std::filesystem::temp_directory_path() / (name + "-" + std::to_string(::getpid()) + suffix));
}

}  // namespace roadload::test
