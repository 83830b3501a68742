#pragma once
// The status files: one text line and one JSON line per interval, appended and never rewritten, so
// `tail -f` follows them and logrotate moves them away (SIGHUP reopens by name). A file that cannot
// be written is retried at every line and never stops the daemon.
#include <string>
#include <string_view>

namespace roadload::firmware {

class StatusLog {
 public:
  StatusLog(std::string text_path, std::string json_path);
  ~StatusLog();
  StatusLog(const StatusLog&) = delete;
  StatusLog& operator=(const StatusLog&) = delete;

  // Opens both; false with the failure in error() (the caller decides whether that is fatal).
  bool open();
  void reopen();
  void text(std::string_view line);
  void json(std::string_view line);
  const std::string& error() const { return error_; }

 private:
  static void put(int& fd, const std::string& path, std::string_view line, std::string& error);
  std::string text_path_, json_path_;
  int text_fd_ = -1, json_fd_ = -1;
  std::string error_;
};

}  // namespace roadload::firmware
