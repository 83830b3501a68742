#include "roadload/io/directory_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace roadload::io {
namespace {

constexpr const char* kLockFile = ".roadloadd.lock";

// The pid the holder wrote, for the message; empty when it cannot be read.
std::string holder(int fd) {
  char buf[32] = {};
  const ssize_t n = pread(fd, buf, sizeof buf - 1, 0);
  if (n <= 0) return {};
  std::string s(buf, static_cast<std::size_t>(n));
  while (!s.empty() && (s.back() == '\n' || s.back() == ' ')) s.pop_back();
  return s;
}

}  // namespace

Parsed<DirectoryLock> DirectoryLock::take(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) return ParseError{dir, 0, "", ec.message()};
  const std::string path = (std::filesystem::path(dir) / kLockFile).string();
  const int fd = open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd < 0) return ParseError{path, 0, "", std::strerror(errno)};
  if (flock(fd, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    const std::string pid = holder(fd);
    close(fd);
    if (err == EWOULDBLOCK) {
      return ParseError{path, 0, "", "the data directory is in use by another roadloadd" + (pid.empty() ? "" : " (pid " + pid + ")")};
    }
    return ParseError{path, 0, "", std::strerror(err)};
  }
  const std::string pid = std::to_string(getpid()) + "\n";
  if (ftruncate(fd, 0) != 0 || pwrite(fd, pid.data(), pid.size(), 0) != static_cast<ssize_t>(pid.size())) {
    const int err = errno;
    close(fd);
    return ParseError{path, 0, "", std::strerror(err)};
  }
  return DirectoryLock(fd);
}

DirectoryLock::~DirectoryLock() {
  if (fd_ >= 0) close(fd_);
}

}  // namespace roadload::io
