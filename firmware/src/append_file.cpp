#include "roadload/firmware/append_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

namespace roadload::firmware {

AppendFile::~AppendFile() { close(); }

bool AppendFile::open(const std::string& path, FrameCompressor* compressor) {
  close();
  compressor_ = compressor;
  frames_ = 0;
  if (!buffer_) buffer_ = std::make_unique<char[]>(capacity_);
  fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0640);
  if (fd_ < 0) {
    errno_ = errno;
    return false;
  }
  struct stat st {};
  written_ = fstat(fd_, &st) == 0 ? static_cast<std::uint64_t>(st.st_size) : 0;
  path_ = path;
  used_ = 0;
  used_lines_ = 0;
  errno_ = 0;
  return true;
}

bool AppendFile::append(std::string_view line) {
  if (fd_ < 0) {
    ++lost_;
    return false;
  }
  // A full buffer goes out now; after a failed frame, not before the next sync(): compressing the
  // same lines again for every line that arrives would cost a core while the disk is full.
  const bool retry = compressor_ == nullptr || errno_ == 0;
  if (used_ + line.size() > capacity_ && !(retry && write_out()) && used_ + line.size() > capacity_) {
    ++lost_;
    return false;
  }
  if (line.size() > capacity_) {
    ++lost_;
    return false;
  }
  std::memcpy(buffer_.get() + used_, line.data(), line.size());
  used_ += line.size();
  ++used_lines_;
  return true;
}

bool AppendFile::flush() {
  if (fd_ < 0) return false;
  // Compressed, the frame stays open; a failure to write the last one stands until a sync succeeds.
  if (compressor_ != nullptr) return errno_ == 0;
  return write_out();
}

bool AppendFile::write_out() {
  if (compressor_ != nullptr) return write_frame();
  std::size_t done = 0;
  while (done < used_) {
    const ssize_t n = ::write(fd_, buffer_.get() + done, used_ - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      errno_ = n < 0 ? errno : ENOSPC;
      // Only whole lines stay in the file: cut what this attempt wrote, retry it all later.
      if (done > 0 && ftruncate(fd_, static_cast<off_t>(written_)) != 0) {
        // The kernel kept a partial write it will not let go of: keep going past it as written.
        written_ += done;
        used_lines_ -= static_cast<std::uint64_t>(std::count(buffer_.get(), buffer_.get() + done, '\n'));
        std::memmove(buffer_.get(), buffer_.get() + done, used_ - done);
        used_ -= done;
      }
      return false;
    }
    done += static_cast<std::size_t>(n);
  }
  written_ += used_;
  used_ = 0;
  used_lines_ = 0;
  errno_ = 0;
  return true;
}

bool AppendFile::write_frame() {
  if (used_ == 0) return true;
  const std::span<const char> frame = compressor_->compress({buffer_.get(), used_});
  if (frame.empty()) {
    errno_ = ENOMEM;
    return false;
  }
  std::size_t done = 0;
  while (done < frame.size()) {
    const ssize_t n = ::write(fd_, frame.data() + done, frame.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      errno_ = n < 0 ? errno : ENOSPC;
      // Half a frame is no frame: cut it, and compress the same lines again at the next try. Should
      // the kernel keep it, the lines are counted lost now and the reader stops at the cut frame.
      if (done > 0 && ftruncate(fd_, static_cast<off_t>(written_)) != 0) {
        written_ += done;
        lost_ += used_lines_;
        used_ = 0;
        used_lines_ = 0;
      }
      return false;
    }
    done += static_cast<std::size_t>(n);
  }
  written_ += frame.size();
  ++frames_;
  used_ = 0;
  used_lines_ = 0;
  errno_ = 0;
  return true;
}

bool AppendFile::sync() {
  if (fd_ < 0) return false;
  if (!write_out()) return false;
  if (fdatasync(fd_) != 0) {
    errno_ = errno;
    return false;
  }
  return true;
}

bool AppendFile::close() {
  if (fd_ < 0) return errno_ == 0;
  const bool ok = sync();
  ::close(fd_);
  fd_ = -1;
  if (!ok) lost_ += used_lines_;
  used_ = 0;
  used_lines_ = 0;
  return ok;
}

}  // namespace roadload::firmware
