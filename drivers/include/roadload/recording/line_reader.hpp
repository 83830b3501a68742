#pragma once
// Reads a text file line by line through a fixed buffer: memory stays bounded whatever the file
// size, and every line comes with its number for error messages. A file that starts with zstd's
// magic number (roadloadd's streams, `zstd` output) is decompressed on the way, frame after frame;
// a stream that ends inside a frame (the recorder stopped while writing it) or a damaged frame is
// an error() after the lines before it.
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "roadload/parse_error.hpp"

namespace roadload::recording {

class LineReader {
 public:
  // Reads of 256 KiB cost no more per line than of 1 MiB (memchr, not read(), is the time), and an
  // analysis holds two readers of three streams at once.
  static constexpr std::size_t kDefaultBuffer = 256 * 1024;
  static constexpr std::size_t kMaxLine = 64 * 1024;

  // Opens `path`; "-" reads standard input.
  static Parsed<LineReader> open(const std::string& path, std::size_t buffer_bytes = kDefaultBuffer);

  // Next line without its terminator; nullopt at end of file or after a read error (error()). A
  // line longer than kMaxLine is skipped whole and given as an empty line with overlong() set: its
  // caller reports it with its number and reads on, never losing the rest of the file.
  std::optional<std::string_view> next();
  bool overlong() const { return overlong_; }
  // The report of the overlong line just given.
  ParseError overlong_error() const;
  long line_number() const { return line_; }
  const std::string& path() const { return path_; }
  const std::optional<ParseError>& error() const { return error_; }

 private:
  struct FileCloser {
    void operator()(std::FILE* f) const;
  };
  struct Zstd;
  struct ZstdDeleter {
    void operator()(Zstd* z) const;
  };
  LineReader(std::string path, std::FILE* f, std::size_t buffer_bytes);
  bool refill();
  bool refill_zstd();
  void detect_compression();
  std::optional<std::string_view> skip_overlong();
  void release();

  std::string path_;
  std::unique_ptr<std::FILE, FileCloser> file_;
  std::unique_ptr<Zstd, ZstdDeleter> zstd_;  // null for plain text
  std::vector<char> buf_;
  std::size_t begin_ = 0;
  std::size_t end_ = 0;
  bool eof_ = false;
  bool overlong_ = false;
  long line_ = 0;
  std::optional<ParseError> error_;
};

}  // namespace roadload::recording
