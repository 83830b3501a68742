#pragma once
// A file the daemon appends whole lines to, through a fixed buffer allocated once. Lines reach the
// kernel at flush() (or when the buffer fills), the disk at sync(). A failed write (disk full, I/O
// error) truncates the file back to its last whole line, keeps the unwritten lines in the buffer
// for the next attempt and refuses new lines only once the buffer is full: each refused line is
// counted, nothing is lost silently, and the file always reads back line by line.
//
// Given a FrameCompressor, the file is a sequence of independent zstd frames instead (`zstdcat`
// gives back the text): a frame is closed and written at each sync() and whenever the buffer
// fills, so a crash or power cut loses at most the open frame; flush() leaves the lines in the
// buffer. A frame that fails to write is cut from the file and compressed again at the next try.
#include <cstdint>
#include <memory>
#include <string>
#include <string_view>

#include "roadload/firmware/frame_compressor.hpp"

namespace roadload::firmware {

class AppendFile {
 public:
  static constexpr std::size_t kBufferBytes = 1 << 18;

  AppendFile() = default;
  // `capacity`: the buffer's bytes, allocated at the first open() and kept for every later file.
  explicit AppendFile(std::size_t capacity) : capacity_(capacity) {}
  AppendFile(const AppendFile&) = delete;
  AppendFile& operator=(const AppendFile&) = delete;
  ~AppendFile();

  // Creates (or appends to) `path`, in frames of `compressor` when one is given (it must outlive
  // the file); false with errno set when it cannot.
  bool open(const std::string& path, FrameCompressor* compressor = nullptr);
  bool is_open() const { return fd_ >= 0; }
  // Buffers a line (with its newline). False when the line was refused and counted as lost.
  bool append(std::string_view line);
  // Hands the buffer to the kernel; false on a write error (the buffer is kept). Compressed: does
  // nothing, the frame stays open until sync().
  bool flush();
  // Writes the buffer (compressed: closes the frame) then fdatasync().
  bool sync();
  // Syncs and closes; false if anything failed.
  bool close();

  // Bytes in the file and, not yet compressed, in the buffer.
  std::uint64_t bytes() const { return written_ + used_; }
  std::uint64_t frames() const { return frames_; }
  std::uint64_t lines_lost() const { return lost_; }
  int last_errno() const { return errno_; }
  const std::string& path() const { return path_; }

 private:
  bool write_out();
  bool write_frame();

  int fd_ = -1;
  FrameCompressor* compressor_ = nullptr;
  std::uint64_t frames_ = 0;
  std::string path_;
  std::size_t capacity_ = kBufferBytes;
  std::unique_ptr<char[]> buffer_;
  std::size_t used_ = 0;
  std::uint64_t used_lines_ = 0;
  std::uint64_t written_ = 0;  // bytes known to be in the file, all whole lines
  std::uint64_t lost_ = 0;
  int errno_ = 0;
};

}  // namespace roadload::firmware
