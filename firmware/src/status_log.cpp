#include "roadload/firmware/status_log.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <filesystem>

namespace roadload::firmware {

namespace {

int open_append(const std::string& path, std::string& error) {
  if (path.empty()) return -1;
  std::error_code ec;
  const auto parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent, ec);
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
  if (fd < 0) error = path + ": " + std::strerror(errno);
  return fd;
}

}  // namespace

StatusLog::StatusLog(std::string text_path, std::string json_path)
    : text_path_(std::move(text_path)), json_path_(std::move(json_path)) {}

StatusLog::~StatusLog() {
  if (text_fd_ >= 0) ::close(text_fd_);
  if (json_fd_ >= 0) ::close(json_fd_);
}

bool StatusLog::open() {
  error_.clear();
  text_fd_ = open_append(text_path_, error_);
  json_fd_ = open_append(json_path_, error_);
  return error_.empty();
}

void StatusLog::reopen() {
  if (text_fd_ >= 0) ::close(text_fd_);
  if (json_fd_ >= 0) ::close(json_fd_);
  text_fd_ = json_fd_ = -1;
  open();
}

void StatusLog::put(int& fd, const std::string& path, std::string_view line, std::string& error) {
  if (path.empty()) return;
  if (fd < 0) fd = open_append(path, error);
  if (fd < 0) return;
  // One write per line: O_APPEND keeps a line whole for a reader tailing the file.
  if (::write(fd, line.data(), line.size()) != static_cast<ssize_t>(line.size())) {
    error = path + ": " + std::strerror(errno);
  }
}

void StatusLog::text(std::string_view line) { put(text_fd_, text_path_, line, error_); }
void StatusLog::json(std::string_view line) { put(json_fd_, json_path_, line, error_); }

}  // namespace roadload::firmware
