#pragma once
// A file the daemon appends whole lines to, through a fixed buffer allocated once. Lines reach the
// kernel at flush() (or when the buffer fills), the disk at sync(). A failed write (disk full, I/O
// error) truncates the file back to its last whole line, keeps the unwritten lines in the buffer
// for the next attempt and refuses new lines only once the buffer is full: each refused line is
// counted, nothing is lost silently, and the file always reads back line by line.
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

namespace roadload::firmware {

class AppendFile {
 public:
  static constexpr std::size_t kBufferBytes = 1 << 18;

  AppendFile() = default;
  AppendFile(const AppendFile&) = delete;
  AppendFile& operator=(const AppendFile&) = delete;
  ~AppendFile();

  // Creates (or appends to) `path`; false with errno set when it cannot.
  bool open(const std::string& path);
  bool is_open() const { return fd_ >= 0; }
  // Buffers a line (with its newline). False when the line was refused and counted as lost.
  bool append(std::string_view line);
  // Hands the buffer to the kernel; false on a write error (the buffer is kept).
  bool flush();
  // flush() then fdatasync().
  bool sync();
  // Syncs and closes; false if anything failed.
  bool close();

  std::uint64_t bytes() const { return written_ + used_; }
  std::uint64_t lines_lost() const { return lost_; }
  int last_errno() const { return errno_; }
  const std::string& path() const { return path_; }

 private:
  int fd_ = -1;
  std::string path_;
  std::unique_ptr<char[]> buffer_;
  std::size_t used_ = 0;
  std::uint64_t used_lines_ = 0;
  std::uint64_t written_ = 0;  // bytes known to be in the file, all whole lines
  std::uint64_t lost_ = 0;
  int errno_ = 0;
};

}  // namespace roadload::firmware
