#pragma once
// Reads a recording folder (or a bare candump log) and merges its streams in capture-time order,
// holding one pending record per stream: memory stays bounded for a drive of any length.
// Malformed lines are counted, the first of them kept with file, line and field, and skipped:
// the caller decides whether that is fatal, and nothing is dropped without being reported.
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <variant>
#include <vector>

#include "roadload/can_frame.hpp"
#include "roadload/parse_error.hpp"
#include "roadload/recording/candump.hpp"
#include "roadload/recording/line_reader.hpp"
#include "roadload/recording/metadata.hpp"
#include "roadload/samples.hpp"

namespace roadload::recording {

using Record = std::variant<CanFrame, AccelSample, GnssFix, WeatherSample>;

// An acceleration beyond this is no sensor's on a truck (the ADXL355 tops out at 8 g): a
// recording's value outside it is malformed, whatever its layout.
inline constexpr double kMaxAccelMps2 = 2000;

// Bad input kept for the report: every error is counted, the first kMaxKept are kept whole.
class ErrorLog {
 public:
  static constexpr std::size_t kMaxKept = 20;
  void add(ParseError e);
  std::uint64_t count() const { return count_; }
  const std::vector<ParseError>& kept() const { return kept_; }
  // The errors in files whose path ends with `name` (a stream: "can.log", "accel.csv", ...), or with
  // `name` compressed.
  std::uint64_t count_in(std::string_view name) const;

 private:
  std::uint64_t count_ = 0;
  std::vector<ParseError> kept_;
  std::vector<std::pair<std::string, std::uint64_t>> by_file_;  // a recording has a handful of files
};

struct StreamCounts {
  std::uint64_t records = 0;
  std::uint64_t ignored_lines = 0;  // lines canplayer would skip too (comments, blank)
  std::uint64_t backwards = 0;      // stamps earlier than the stream's previous one
};

class Stream {
 public:
  virtual ~Stream() = default;
  // Next good record of this stream; false at the end. Bad lines go to `errors`.
  virtual bool next(Record& out, ErrorLog& errors) = 0;
  virtual const char* name() const = 0;
  // The interface names of a CAN stream's frames; null for the others.
  virtual const InterfaceTable* interfaces() const { return nullptr; }
  const StreamCounts& counts() const { return counts_; }

 protected:
  // A record handed on: counted, and counted again when its stamp runs backwards.
  void count(CaptureTime t) {
    if (t < last_counted_) ++counts_.backwards;
    last_counted_ = t;
    ++counts_.records;
  }
  StreamCounts counts_;

 private:
  CaptureTime last_counted_{};
};

// A candump -L log, also usable alone (decode of a bare log, benchmarks).
class CandumpStream final : public Stream {
 public:
  // `interfaces`: the names a previous segment of the drive gave indices to, kept for this one.
  static Parsed<std::unique_ptr<CandumpStream>> open(const std::string& path, const InterfaceTable* interfaces = nullptr);
  bool next(Record& out, ErrorLog& errors) override;
  // The same without the variant, for the tight decode loop.
  bool next_frame(CanFrame& out, ErrorLog& errors);
  const char* name() const override { return kCanFile; }
  const InterfaceTable* interfaces() const override { return &ifaces_; }

 private:
  explicit CandumpStream(LineReader lines) : lines_(std::move(lines)) {}
  LineReader lines_;
  InterfaceTable ifaces_;
};

// Which of a folder's streams to read (a replay source reads only its own).
enum StreamMask : unsigned {
  kCanStream = 1,
  kAccelStream = 2,
  kGnssStream = 4,
  kWeatherStream = 8,
  kAllStreams = 15,
};
// A record's capture stamp, whatever its stream.
CaptureTime stamp_of(const Record& r);
// DIR/meta.toml, read and parsed.
Parsed<Metadata> read_metadata(const std::filesystem::path& dir);

inline constexpr unsigned kStreamBits[] = {kCanStream, kAccelStream, kGnssStream, kWeatherStream};
// A stream's file name in a recording folder, and the stream read from it.
const char* stream_file(unsigned bit);
// What a folder lacks when it holds none of `streams`, e.g. "no can.log".
std::string no_streams(unsigned streams);
// The file that holds stream file `name` in `dir`: `name` itself or, compressed, `name.zst`; nullopt
// when neither exists. A plain file is read first when a folder holds both (a copy decompressed
// beside its original).
std::optional<std::filesystem::path> find_stream(const std::filesystem::path& dir, const char* name);
// Whether `dir` holds the stream: its file, compressed or not, or for the accelerometers their FLAC
// files (recording/flac_accel.hpp), read merged with accel.csv when the folder has both.
bool has_stream(const std::filesystem::path& dir, unsigned bit);
Parsed<std::unique_ptr<Stream>> open_stream(unsigned bit, const std::filesystem::path& dir, const InterfaceTable* interfaces);

// What a command given several recordings reads: one path is itself; several must be segments of
// one roadloadd run (the same recording_id in meta.toml, segment numbers following each other,
// given in any order), returned in order. Anything else is an error naming the path and why: the
// command refuses it as a usage error (64) rather than read some of it.
Parsed<std::vector<std::string>> join_segments(std::span<const std::string> paths);

class RecordingReader {
 public:
  // `path` is a recording folder or a candump log file.
  static Parsed<RecordingReader> open(const std::string& path, unsigned streams = kAllStreams);
  // The segments of one drive as join_segments ordered them, read as one recording: each stream
  // runs through its file in every segment in turn, the interface names carried across, and the
  // first segment's meta.toml stands for the drive. A segment whose stamps start before the
  // previous one's end is reported as a malformed line of its file.
  static Parsed<RecordingReader> open_drive(std::span<const std::string> segments, unsigned streams = kAllStreams);

  // Next record across all streams, earliest stamp first (ties: can, accel, gnss, weather).
  const Record* next();
  // The next record into `out`; false at the end. One stream parses straight into it.
  bool next_into(Record& out);

  const Metadata& metadata() const { return meta_; }
  bool has_metadata() const { return has_meta_; }
  const InterfaceTable& interfaces() const;
  const ErrorLog& errors() const { return errors_; }
  const std::vector<std::unique_ptr<Stream>>& streams() const { return streams_; }

 private:
  RecordingReader() = default;
  Metadata meta_;
  bool has_meta_ = false;
  std::vector<std::unique_ptr<Stream>> streams_;
  std::vector<Record> heads_;
  // Each head's stamp, an ended stream's the end of time: the merge is a plain minimum.
  std::vector<CaptureTime> stamps_;
  Record current_;
  ErrorLog errors_;
  bool primed_ = false;
  // The stream whose head next() returned last: it moves on at the next call, so the record is
  // handed out where it lies rather than copied.
  std::size_t taken_ = 0;
  bool has_taken_ = false;
  // The oldest head of the other streams when taken_ was chosen, and its stream.
  std::size_t rival_ = 0;
  CaptureTime rival_t_ = CaptureTime::max();
};

}  // namespace roadload::recording
