// A drive cut into segments by roadloadd (size, time, SIGUSR1), read back as one recording.
#include <algorithm>
#include <filesystem>

#include "roadload/recording/reader.hpp"

namespace roadload::recording {
namespace {

namespace fs = std::filesystem;

// One stream through its file in each segment in turn. Counts are the segments' together; a
// segment that starts before the previous one ended is not the same drive's continuation, and
// says so once as a malformed line of its file.
class ChainStream final : public Stream {
 public:
  ChainStream(unsigned bit, std::vector<fs::path> folders) : bit_(bit), folders_(std::move(folders)) {}

  bool next(Record& out, ErrorLog& errors) override {
    for (;;) {
      if (current_ && current_->next(out, errors)) {
        check_order(stamp_of(out), errors);
        counts_ = add(done_, current_->counts());
        return true;
      }
      if (current_) done_ = add(done_, current_->counts());
      counts_ = done_;
      if (!open_next(errors)) return false;
    }
  }
  const char* name() const override { return stream_file(bit_); }
  const InterfaceTable* interfaces() const override { return current_ ? current_->interfaces() : carried_.get(); }

 private:
  static StreamCounts add(StreamCounts a, const StreamCounts& b) {
    a.records += b.records;
    a.ignored_lines += b.ignored_lines;
    a.backwards += b.backwards;
    return a;
  }

  bool open_next(ErrorLog& errors) {
    if (current_ && current_->interfaces() != nullptr) carried_ = std::make_unique<InterfaceTable>(*current_->interfaces());
    current_.reset();
    while (next_folder_ < folders_.size()) {
      const fs::path& dir = folders_[next_folder_++];
      if (!has_stream(dir, bit_)) continue;
      auto s = open_stream(bit_, dir, carried_.get());
      if (!s) {
        errors.add(s.error());
        continue;
      }
      current_ = std::move(s.value());
      segment_start_ = true;
      return true;
    }
    return false;
  }

  void check_order(CaptureTime t, ErrorLog& errors) {
    if (segment_start_ && seen_ && t < last_) {
      const fs::path& dir = folders_[next_folder_ - 1];
      errors.add(ParseError{find_stream(dir, stream_file(bit_)).value_or(dir / stream_file(bit_)).string(), 0, "t",
                            "this segment starts before the previous one ends: not the next part of the drive"});
    }
    segment_start_ = false;
    seen_ = true;
    last_ = std::max(last_, t);
  }

  unsigned bit_;
  std::vector<fs::path> folders_;
  std::size_t next_folder_ = 0;
  std::unique_ptr<Stream> current_;
  std::unique_ptr<InterfaceTable> carried_;
  StreamCounts done_;
  bool segment_start_ = false, seen_ = false;
  CaptureTime last_{};
};

struct Segment {
  std::string path;
  Metadata meta;
};

Parsed<Segment> read_segment(const std::string& path) {
  std::error_code ec;
  const fs::path meta_path = fs::path(path) / kMetaFile;
  if (!fs::is_directory(path, ec) || !fs::is_regular_file(meta_path, ec)) {
    return ParseError{path, 0, "", "not a recording folder with a meta.toml: only segments of one drive can be joined"};
  }
  auto meta = read_metadata(path);
  if (!meta) return meta.error();
  if (meta.value().recording_id.empty() || meta.value().segment < 1) {
    return ParseError{meta_path.string(), 0, "recording_id",
                      "not a segment of a logger's drive (no recording_id and segment): give one recording at a time"};
  }
  return Segment{path, std::move(meta.value())};
}

}  // namespace

Parsed<std::vector<std::string>> join_segments(std::span<const std::string> paths) {
  if (paths.size() <= 1) return std::vector<std::string>(paths.begin(), paths.end());
  std::vector<Segment> segments;
  for (const std::string& p : paths) {
    auto s = read_segment(p);
    if (!s) return s.error();
    segments.push_back(std::move(s.value()));
  }
  std::sort(segments.begin(), segments.end(), [](const Segment& a, const Segment& b) { return a.meta.segment < b.meta.segment; });
  std::vector<std::string> ordered{segments[0].path};
  for (std::size_t i = 1; i < segments.size(); ++i) {
    const Segment& prev = segments[i - 1];
    const Segment& s = segments[i];
    const std::string meta_path = (fs::path(s.path) / kMetaFile).string();
    if (s.meta.recording_id != segments[0].meta.recording_id) {
      return ParseError{
          meta_path, 0, "recording_id",
          "'" + s.meta.recording_id + "' is another drive than " + segments[0].path + "'s '" + segments[0].meta.recording_id + "'"};
    }
    if (s.meta.segment != prev.meta.segment + 1) {
      return ParseError{meta_path, 0, "segment",
                        s.meta.segment == prev.meta.segment
                            ? "segment " + std::to_string(s.meta.segment) + " given twice (also " + prev.path + ")"
                            : "segment " + std::to_string(prev.meta.segment + 1) + " of the drive is missing between " + prev.path +
                                  " and " + s.path};
    }
    ordered.push_back(s.path);
  }
  return ordered;
}

Parsed<RecordingReader> RecordingReader::open_drive(std::span<const std::string> segments, unsigned streams) {
  if (segments.size() == 1) return open(segments[0], streams);
  if (segments.empty()) return ParseError{"", 0, "", "no recording given"};
  auto meta = read_metadata(segments[0]);  // join_segments read it already: a segment has one
  if (!meta) return meta.error();
  RecordingReader r;
  r.meta_ = std::move(meta.value());
  r.has_meta_ = true;
  const std::vector<fs::path> folders(segments.begin(), segments.end());
  for (unsigned bit : kStreamBits) {
    if ((streams & bit) == 0) continue;
    const bool any = std::any_of(folders.begin(), folders.end(), [&](const fs::path& d) { return has_stream(d, bit); });
    if (any) r.streams_.push_back(std::make_unique<ChainStream>(bit, folders));
  }
  if (r.streams_.empty()) return ParseError{segments[0], 0, "", no_streams(streams) + " in any segment"};
  return r;
}

}  // namespace roadload::recording
