#pragma once
// An exclusive hold on a directory for one process: two daemons writing one data directory would
// delete each other's open segments under a quota and interleave lines in one segment. The lock
// is flock(2) on a file inside the directory, so the kernel releases it when the process ends,
// however it ends, and a stale lock file never blocks a restart.
#include <string>

#include "roadload/parse_error.hpp"

namespace roadload::io {

class DirectoryLock {
 public:
  // Creates `dir` when missing and takes `dir`/.roadloadd.lock, writing this process's id into it.
  // Fails naming the holder's pid when another process holds it.
  static Parsed<DirectoryLock> take(const std::string& dir);

  DirectoryLock(DirectoryLock&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }
  DirectoryLock& operator=(DirectoryLock&&) = delete;
  DirectoryLock(const DirectoryLock&) = delete;
  ~DirectoryLock();

 private:
  explicit DirectoryLock(int fd) : fd_(fd) {}
  int fd_ = -1;
};

}  // namespace roadload::io
