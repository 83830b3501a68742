#include "roadload/recording/line_reader.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>

namespace roadload::recording {

void LineReader::FileCloser::operator()(std::FILE* f) const {
  if (f != nullptr && f != stdin) std::fclose(f);
}

LineReader::LineReader(std::string path, std::FILE* f, std::size_t buffer_bytes)
    : path_(std::move(path)), file_(f), buf_(std::max(buffer_bytes, kMaxLine * 2)) {}

Parsed<LineReader> LineReader::open(const std::string& path, std::size_t buffer_bytes) {
  std::FILE* f = path == "-" ? stdin : std::fopen(path.c_str(), "rb");
  if (f == nullptr) return ParseError{path, 0, "", std::strerror(errno)};
  return LineReader(path, f, buffer_bytes);
}

std::optional<std::string_view> LineReader::skip_overlong() {
  overlong_ = true;
  for (;;) {
    begin_ = end_;
    if (!refill()) {
      if (error_) return std::nullopt;
      ++line_;
      return std::string_view();
    }
    const char* start = buf_.data() + begin_;
    if (const auto* nl = static_cast<const char*>(std::memchr(start, '\n', end_ - begin_))) {
      begin_ += static_cast<std::size_t>(nl - start) + 1;
      ++line_;
      return std::string_view();
    }
  }
}

bool LineReader::refill() {
  if (eof_) return false;
  if (begin_ > 0) {
    std::memmove(buf_.data(), buf_.data() + begin_, end_ - begin_);
    end_ -= begin_;
    begin_ = 0;
  }
  const std::size_t n = std::fread(buf_.data() + end_, 1, buf_.size() - end_, file_.get());
  end_ += n;
  if (n == 0) {
    if (std::ferror(file_.get())) error_ = ParseError{path_, line_ + 1, "", std::strerror(errno)};
    eof_ = true;
  }
  return n > 0;
}

ParseError LineReader::overlong_error() const {
  return ParseError{path_, line_, "", "line longer than " + std::to_string(kMaxLine) + " bytes, skipped"};
}

std::optional<std::string_view> LineReader::next() {
  if (error_) return std::nullopt;
  overlong_ = false;
  for (;;) {
    const char* start = buf_.data() + begin_;
    const auto* nl = static_cast<const char*>(std::memchr(start, '\n', end_ - begin_));
    if (nl != nullptr) {
      std::size_t len = static_cast<std::size_t>(nl - start);
      begin_ += len + 1;
      ++line_;
      if (len > 0 && start[len - 1] == '\r') --len;
      return std::string_view(start, len);
    }
    if (end_ - begin_ > kMaxLine) return skip_overlong();
    if (!refill()) {
      if (error_ || begin_ == end_) return std::nullopt;
      // Last line without a newline.
      std::string_view last(buf_.data() + begin_, end_ - begin_);
      begin_ = end_;
      ++line_;
      return last;
    }
  }
}

}  // namespace roadload::recording
