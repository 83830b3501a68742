#include "roadload/recording/line_reader.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>

#include <zstd.h>

namespace roadload::recording {

namespace {
constexpr unsigned char kZstdMagic[4] = {0x28, 0xb5, 0x2f, 0xfd};
}  // namespace

struct LineReader::Zstd {
  ZSTD_DStream* stream = ZSTD_createDStream();
  std::vector<char> in = std::vector<char>(ZSTD_DStreamInSize());
  ZSTD_inBuffer pending{in.data(), 0, 0};
  bool file_done = false;
  bool inside_frame = false;
  std::uint64_t frames = 0;
};

void LineReader::ZstdDeleter::operator()(Zstd* z) const {
  ZSTD_freeDStream(z->stream);
  delete z;
}

void LineReader::FileCloser::operator()(std::FILE* f) const {
  if (f != nullptr && f != stdin) std::fclose(f);
}

LineReader::LineReader(std::string path, std::FILE* f, std::size_t buffer_bytes)
    : path_(std::move(path)), file_(f), buf_(std::max(buffer_bytes, kMaxLine * 2)) {}

Parsed<LineReader> LineReader::open(const std::string& path, std::size_t buffer_bytes) {
  std::FILE* f = path == "-" ? stdin : std::fopen(path.c_str(), "rb");
  if (f == nullptr) return ParseError{path, 0, "", std::strerror(errno)};
  LineReader r(path, f, buffer_bytes);
  r.detect_compression();
  return r;
}

// Standard input cannot seek back: the first bytes read stay in the line buffer as text, or move
// to the decompressor's input when they are zstd's magic number.
void LineReader::detect_compression() {
  end_ = std::fread(buf_.data(), 1, sizeof kZstdMagic, file_.get());
  if (end_ < sizeof kZstdMagic || std::memcmp(buf_.data(), kZstdMagic, sizeof kZstdMagic) != 0) return;
  zstd_.reset(new Zstd);
  std::memcpy(zstd_->in.data(), buf_.data(), end_);
  zstd_->pending = {zstd_->in.data(), end_, 0};
  end_ = 0;
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
  if (zstd_) return refill_zstd();
  const std::size_t n = std::fread(buf_.data() + end_, 1, buf_.size() - end_, file_.get());
  end_ += n;
  if (n == 0) {
    if (std::ferror(file_.get())) error_ = ParseError{path_, line_ + 1, "", std::strerror(errno)};
    eof_ = true;
  }
  return n > 0;
}

bool LineReader::refill_zstd() {
  Zstd& z = *zstd_;
  for (;;) {
    if (z.pending.pos == z.pending.size) {
      if (z.file_done) {
        if (z.inside_frame)
          error_ = ParseError{path_, line_ + 1, "",
                              "the compressed stream ends inside its frame " + std::to_string(z.frames + 1) +
                                  ": the lines being written when it stopped are lost"};
        eof_ = true;
        return false;
      }
      const std::size_t n = std::fread(z.in.data(), 1, z.in.size(), file_.get());
      if (n == 0) {
        if (std::ferror(file_.get())) {
          error_ = ParseError{path_, line_ + 1, "", std::strerror(errno)};
          eof_ = true;
          return false;
        }
        z.file_done = true;
        continue;
      }
      z.pending = {z.in.data(), n, 0};
    }
    ZSTD_outBuffer out{buf_.data() + end_, buf_.size() - end_, 0};
    const std::size_t left = ZSTD_decompressStream(z.stream, &out, &z.pending);
    if (ZSTD_isError(left)) {
      error_ = ParseError{path_, line_ + 1, "",
                          "damaged compressed stream in frame " + std::to_string(z.frames + 1) + ": " + ZSTD_getErrorName(left)};
      eof_ = true;
      return false;
    }
    if (left == 0) ++z.frames;
    z.inside_frame = left != 0;
    end_ += out.pos;
    if (out.pos > 0) return true;
  }
}

ParseError LineReader::overlong_error() const {
  return ParseError{path_, line_, "", "line longer than " + std::to_string(kMaxLine) + " bytes, skipped"};
}

// An analysis holds its readers past their end (their errors are reported last): at its end a
// stream gives its buffers back.
void LineReader::release() {
  zstd_.reset();
  buf_ = std::vector<char>();
  begin_ = end_ = 0;
  file_.reset();
}

std::optional<std::string_view> LineReader::next() {
  if (error_ || buf_.empty()) return std::nullopt;
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
      if (error_ || begin_ == end_) {
        release();
        return std::nullopt;
      }
      // Last line without a newline.
      std::string_view last(buf_.data() + begin_, end_ - begin_);
      begin_ = end_;
      ++line_;
      return last;
    }
  }
}

}  // namespace roadload::recording
