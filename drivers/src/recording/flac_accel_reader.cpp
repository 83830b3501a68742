// Reading the accelerometers' FLAC files through libFLAC: any standard FLAC encoder's output of the
// layout reads, not only the recorder's own, and a damaged frame is found by its CRC and skipped.
#include <FLAC/stream_decoder.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string_view>
#include <system_error>

#include "roadload/recording/flac_accel.hpp"

namespace fs = std::filesystem;

namespace roadload::recording {
namespace {

// One sensor's file, a decoded frame at a time.
class SensorFile {
 public:
  static Parsed<std::unique_ptr<SensorFile>> open(const fs::path& path) {
    std::unique_ptr<SensorFile> f(new SensorFile(path.string()));
    f->dec_ = FLAC__stream_decoder_new();
    if (f->dec_ == nullptr) return ParseError{f->path_, 0, "", "out of memory"};
    FLAC__stream_decoder_set_metadata_respond(f->dec_, FLAC__METADATA_TYPE_VORBIS_COMMENT);
    if (FLAC__stream_decoder_init_file(f->dec_, f->path_.c_str(), &SensorFile::on_frame, &SensorFile::on_metadata,
                                       &SensorFile::on_error, f.get()) != FLAC__STREAM_DECODER_INIT_STATUS_OK) {
      return ParseError{f->path_, 0, "file", "cannot be opened"};
    }
    if (!FLAC__stream_decoder_process_until_end_of_metadata(f->dec_) || !f->pending_.empty()) {
      return f->pending_.empty() ? ParseError{f->path_, 0, "header", "not a FLAC stream"} : f->pending_.front();
    }
    if (!f->sensor_ || !(f->step_mps2_ > 0)) {
      return ParseError{f->path_, 0, f->sensor_ ? "ROADLOAD_STEP_MPS2" : "ROADLOAD_SENSOR",
                        "missing from the VORBIS_COMMENT: not a roadload accelerometer stream"};
    }
    return f;
  }
  ~SensorFile() {
    if (dec_ != nullptr) FLAC__stream_decoder_delete(dec_);
  }
  SensorFile(const SensorFile&) = delete;
  SensorFile& operator=(const SensorFile&) = delete;

  std::uint8_t sensor() const { return *sensor_; }
  double step_mps2() const { return step_mps2_; }
  double rate_hz() const { return rate_hz_; }

  bool next(AccelSample& out, ErrorLog& errors) {
    for (;;) {
      while (pos_ == count_) {
        if (!decode(errors)) return false;
      }
      const std::size_t i = pos_++;
      // The sensors' blocks are read in turns with the analysis's work between: without this, the
      // loads of a sample's stamp waited on memory.
      __builtin_prefetch(block_.data() + std::min(i + kPrefetch, count_ - 1));
      const Counts& c = block_[i];
      const std::uint64_t number = frame_first_ + i;
      const std::int64_t seconds = c.s, ns = c.ns;
      if (seconds < 0 || ns < 0 || ns >= kNsPerS) {
        errors.add(ParseError{path_, 0, "sample " + std::to_string(number) + " stamp", "outside its range"});
        continue;
      }
      out.t = capture_time_from_ns(seconds * kNsPerS + ns);
      out.sensor = *sensor_;
      out.x_mps2 = c.x * step_mps2_;
      out.y_mps2 = c.y * step_mps2_;
      out.z_mps2 = c.z * step_mps2_;
      if (std::max({std::abs(out.x_mps2), std::abs(out.y_mps2), std::abs(out.z_mps2)}) > kMaxAccelMps2) {
        errors.add(ParseError{path_, 0, "sample " + std::to_string(number), "acceleration beyond 2000 m/s^2"});
        continue;
      }
      return true;
    }
  }

 private:
  explicit SensorFile(std::string path) : path_(std::move(path)) {}

  std::string field() const { return "frame after sample " + std::to_string(expected_); }

  // The next frame into block_; false at the end of the stream (the decoder is then gone).
  bool decode(ErrorLog& errors) {
    pos_ = count_ = 0;
    const bool more = !ended_ && FLAC__stream_decoder_process_single(dec_) &&
                      FLAC__stream_decoder_get_state(dec_) != FLAC__STREAM_DECODER_END_OF_STREAM;
    for (ParseError& e : pending_) errors.add(std::move(e));
    pending_.clear();
    if (more || count_ > 0) return true;
    if (!ended_ && FLAC__stream_decoder_get_state(dec_) != FLAC__STREAM_DECODER_END_OF_STREAM) {
      errors.add(ParseError{path_, 0, field(), "cannot be decoded further"});
    }
    ended_ = true;
    // A reader is held past its end (an analysis reports errors last): its decoder and block go now.
    if (dec_ != nullptr) FLAC__stream_decoder_delete(dec_);
    dec_ = nullptr;
    block_ = std::vector<Counts>();
    return false;
  }

  static FLAC__StreamDecoderWriteStatus on_frame(const FLAC__StreamDecoder*, const FLAC__Frame* frame,
                                                 const FLAC__int32* const buffer[], void* self) {
    auto& f = *static_cast<SensorFile*>(self);
    const FLAC__FrameHeader& h = frame->header;
    if (h.channels != 5 || h.bits_per_sample != 32) {
      f.pending_.push_back(ParseError{f.path_, 0, f.field(), "not five 32-bit channels (x, y, z, s, ns)"});
      return FLAC__STREAM_DECODER_WRITE_STATUS_ABORT;
    }
    const std::uint64_t first = h.number_type == FLAC__FRAME_NUMBER_TYPE_SAMPLE_NUMBER ? h.number.sample_number : f.expected_;
    if (first != f.expected_) {
      f.pending_.push_back(
          ParseError{f.path_, 0, f.field(), "samples " + std::to_string(f.expected_) + " to " + std::to_string(first) + " lost"});
    }
    // libFLAC stands silence in for a frame it could not decode (its CRC failed, or it was lost
    // between two good ones), to keep the samples in step. A stamp of zero in every sample is that
    // silence, never data: the loss is reported, and those zeros are not read as samples.
    if (std::all_of(buffer[3], buffer[3] + h.blocksize, [](FLAC__int32 v) { return v == 0; }) &&
        std::all_of(buffer[4], buffer[4] + h.blocksize, [](FLAC__int32 v) { return v == 0; })) {
      f.pending_.push_back(
          ParseError{f.path_, 0, f.field(),
                     "samples " + std::to_string(first) + " to " + std::to_string(first + h.blocksize - 1) + " damaged: not read"});
      f.expected_ = first + h.blocksize;
      return FLAC__STREAM_DECODER_WRITE_STATUS_CONTINUE;
    }
    // Kept as the decoder's counts, half an AccelSample's bytes, a sample's five together: the eight
    // sensors' blocks are read in turns with the whole analysis between, and did not stay in cache.
    f.block_.resize(h.blocksize);
    for (unsigned i = 0; i < h.blocksize; ++i) f.block_[i] = {buffer[0][i], buffer[1][i], buffer[2][i], buffer[3][i], buffer[4][i]};
    f.frame_first_ = first;
    f.count_ = h.blocksize;
    f.expected_ = first + h.blocksize;
    return FLAC__STREAM_DECODER_WRITE_STATUS_CONTINUE;
  }

  static void on_metadata(const FLAC__StreamDecoder*, const FLAC__StreamMetadata* m, void* self) {
    auto& f = *static_cast<SensorFile*>(self);
    if (m->type == FLAC__METADATA_TYPE_STREAMINFO) f.rate_hz_ = m->data.stream_info.sample_rate;
    if (m->type != FLAC__METADATA_TYPE_VORBIS_COMMENT) return;
    for (FLAC__uint32 i = 0; i < m->data.vorbis_comment.num_comments; ++i) {
      const auto& c = m->data.vorbis_comment.comments[i];
      const std::string_view entry(reinterpret_cast<const char*>(c.entry), c.length);
      const auto eq = entry.find('=');
      if (eq == std::string_view::npos) continue;
      const std::string_view key = entry.substr(0, eq), value = entry.substr(eq + 1);
      if (key == "ROADLOAD_SENSOR") {
        unsigned id = 0;
        const auto r = std::from_chars(value.data(), value.data() + value.size(), id);
        if (r.ec == std::errc{} && r.ptr == value.data() + value.size() && id <= 255) f.sensor_ = static_cast<std::uint8_t>(id);
      } else if (key == "ROADLOAD_STEP_MPS2") {
        const auto r = std::from_chars(value.data(), value.data() + value.size(), f.step_mps2_);
        if (r.ec != std::errc{} || r.ptr != value.data() + value.size() || !std::isfinite(f.step_mps2_)) f.step_mps2_ = 0;
      }
    }
  }

  static void on_error(const FLAC__StreamDecoder*, FLAC__StreamDecoderErrorStatus status, void* self) {
    auto& f = *static_cast<SensorFile*>(self);
    f.pending_.push_back(ParseError{f.path_, 0, f.field(), FLAC__StreamDecoderErrorStatusString[status]});
  }

  std::string path_;
  FLAC__StreamDecoder* dec_ = nullptr;
  std::optional<std::uint8_t> sensor_;
  double step_mps2_ = 0;
  double rate_hz_ = 0;
  struct Counts {
    FLAC__int32 x, y, z, s, ns;
  };
  static constexpr std::size_t kPrefetch = 4;  // samples read ahead
  std::vector<Counts> block_;                  // the frame being read
  std::uint64_t frame_first_ = 0;              // its first sample's number
  std::size_t count_ = 0, pos_ = 0;
  std::uint64_t expected_ = 0;  // the next sample number
  std::vector<ParseError> pending_;
  bool ended_ = false;
};

// accel.csv's rows (when the folder has one) and each sensor's FLAC file, merged by stamp; a tie
// goes to accel.csv, then to the lower sensor id.
class AccelFlacStream final : public Stream {
 public:
  AccelFlacStream(std::unique_ptr<Stream> text, std::vector<std::unique_ptr<SensorFile>> files)
      : text_(std::move(text)), files_(std::move(files)), heads_(files_.size() + 1), stamps_(files_.size() + 1, kEnded) {}

  bool next(Record& out, ErrorLog& errors) override {
    if (!primed_) {
      for (std::size_t i = 0; i < heads_.size(); ++i) pull(i, errors);
      primed_ = true;
    }
    // The oldest head, the first of equal ones: a plain minimum over the stamps, a stream that has
    // ended holding kEnded (a branch per stream on whether it lives cost more than the merge). The
    // sensors take turns, so which stream wins is not predictable: selects, not branches.
    std::size_t best = 0;
    std::int64_t best_t = stamps_[0];
    for (std::size_t i = 1; i < stamps_.size(); ++i) {
      const bool older = stamps_[i] < best_t;
      best = older ? i : best;
      best_t = older ? stamps_[i] : best_t;
    }
    if (best_t == kEnded) return false;
    const AccelSample s = heads_[best];
    pull(best, errors);
    count(s.t);
    out = s;
    return true;
  }
  const char* name() const override { return kAccelFile; }

 private:
  static constexpr std::int64_t kEnded = std::numeric_limits<std::int64_t>::max();

  void pull(std::size_t i, ErrorLog& errors) {
    AccelSample& out = heads_[i];
    bool got = false;
    if (i > 0) {
      got = files_[i - 1]->next(out, errors);
    } else if (text_ && text_->next(record_, errors)) {
      out = std::get<AccelSample>(record_);
      got = true;
    }
    stamps_[i] = got ? to_ns(out.t) : kEnded;
  }

  std::unique_ptr<Stream> text_;
  std::vector<std::unique_ptr<SensorFile>> files_;
  std::vector<AccelSample> heads_;    // [0] accel.csv's, then each file's
  std::vector<std::int64_t> stamps_;  // the heads' stamps
  Record record_;
  bool primed_ = false;
};

}  // namespace

std::vector<fs::path> find_accel_flac(const fs::path& dir) {
  std::vector<std::pair<std::uint8_t, fs::path>> found;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (const auto id = accel_flac_sensor(it->path().filename().string())) found.emplace_back(*id, it->path());
  }
  std::sort(found.begin(), found.end());
  std::vector<fs::path> out;
  for (auto& f : found) out.push_back(std::move(f.second));
  return out;
}

Parsed<AccelFlacInfo> read_accel_flac_info(const fs::path& path) {
  auto f = SensorFile::open(path);
  if (!f) return f.error();
  return AccelFlacInfo{f.value()->sensor(), f.value()->rate_hz(), f.value()->step_mps2()};
}

Parsed<std::unique_ptr<Stream>> open_accel_flac(const std::vector<fs::path>& files, std::unique_ptr<Stream> text) {
  std::vector<std::unique_ptr<SensorFile>> open;
  for (const fs::path& p : files) {
    auto f = SensorFile::open(p);
    if (!f) return f.error();
    open.push_back(std::move(f.value()));
  }
  return std::unique_ptr<Stream>(new AccelFlacStream(std::move(text), std::move(open)));
}

}  // namespace roadload::recording
