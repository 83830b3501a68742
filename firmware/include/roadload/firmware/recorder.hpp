#pragma once
// The daemon's recording: a data directory of segments, each a recording folder
// (docs/recording-format.md) named by its UTC start, `20261122T054012Z-0001`. A segment ends after
// segment_max_s or segment_max_mib, or on SIGUSR1; the oldest segments are deleted while the
// directory holds more than the quota. Lines reach the kernel within a second and the disk at
// every fsync interval, so a crash or SIGKILL loses at most that interval and every file reads
// back whole. A write error (disk full) is reported and retried each tick; the lines that did not
// fit meanwhile are counted as lost. With a compression level, each stream is written as zstd
// frames (`can.log.zst`, ...) closed at every fsync: the same interval is all a crash can lose.
// An accelerometer whose samples are whole steps of a known size goes to its own FLAC file
// (`accel-ID.flac`, recording/flac_accel.hpp) instead, its frame also closed at every fsync.
#include <array>
#include <cstdint>
#include <deque>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "roadload/can_frame.hpp"
#include "roadload/firmware/append_file.hpp"
#include "roadload/recording/flac_encoder.hpp"
#include "roadload/recording/metadata.hpp"
#include "roadload/recording/writer.hpp"
#include "roadload/samples.hpp"
#include "roadload/time.hpp"

namespace roadload::firmware {

// An accelerometer recorded as FLAC counts: its id, nominal rate and step (m/s^2 per count).
struct AccelFlacSensor {
  std::uint8_t sensor = 0;
  double rate_hz = 0;
  double step_mps2 = 0;
};

struct RecorderConfig {
  std::string data_dir;
  Nanoseconds fsync_interval{1'000'000'000};
  Nanoseconds segment_max{3600'000'000'000};
  std::uint64_t segment_max_bytes = 512ull << 20;
  std::uint64_t quota_bytes = 8192ull << 20;
  int compression_level = 1;                // zstd's; 0 writes plain text
  std::vector<AccelFlacSensor> accel_flac;  // the others go to accel.csv
};

struct RecorderStatus {
  std::string segment;                 // current segment folder name, empty when none is open
  std::uint64_t lines = 0;             // lines (and FLAC samples) accepted since start
  std::uint64_t lines_lost = 0;        // refused after write errors
  std::uint64_t segments = 0;          // started since start
  std::uint64_t segments_deleted = 0;  // for the quota
  std::uint64_t bytes_in_dir = 0;
  int error = 0;           // errno of the last failure, 0 once writing works again
  std::string error_text;  // what failed, with the path
};

class Recorder {
 public:
  Recorder(RecorderConfig config, recording::Metadata meta, std::vector<std::string> interfaces);
  ~Recorder();
  Recorder(const Recorder&) = delete;
  Recorder& operator=(const Recorder&) = delete;

  void write(const CanFrame& f);
  void write(const AccelSample& s);
  void write(const GnssFix& s);
  void write(const WeatherSample& s);
  // Flushes each second, syncs at the fsync interval, rotates, keeps the quota, retries failures.
  void tick(CaptureTime now);
  // Ends the current segment; the next write or tick starts another (SIGUSR1, shutdown).
  void end_segment();
  const RecorderStatus& status() const { return status_; }
  const std::string& recording_id() const { return meta_.recording_id; }

 private:
  struct Stream {
    AppendFile file;
    const char* name;
    std::string_view header;
  };
  // One accelerometer's FLAC stream: its encoder and file live as long as the recorder, so a new
  // segment allocates nothing.
  struct FlacStream {
    // Room for two frames at their largest (every channel verbatim): a frame the disk refused, and
    // the next.
    static constexpr std::size_t kBufferBytes = 2 * recording::FlacEncoder::kMaxFrameBytes;
    AccelFlacSensor sensor;
    std::unique_ptr<recording::FlacEncoder> encoder;
    AppendFile file{kBufferBytes};
  };
  void write_flac(FlacStream& f, const AccelSample& s);
  // Appends what the encoder gave (a frame, or nothing); its samples are counted lost if refused.
  void put(FlacStream& f, std::span<const std::uint8_t> bytes, std::uint64_t samples_before);
  bool flush_file(AppendFile& file, bool sync);
  bool start_segment(CaptureTime now);
  void append(Stream& s, std::string_view line);
  void note_error(const std::string& what, int err);
  void scan_data_dir();
  void keep_quota();
  std::uint64_t segment_bytes() const;

  RecorderConfig config_;
  std::unique_ptr<FrameCompressor> compressor_;  // null for plain text
  recording::Metadata meta_;
  std::vector<std::string> interfaces_;
  Stream can_{{}, recording::kCanFile, {}};
  Stream accel_{{}, recording::kAccelFormat.file, recording::kAccelFormat.header};
  Stream gnss_{{}, recording::kGnssFormat.file, recording::kGnssFormat.header};
  Stream weather_{{}, recording::kWeatherFormat.file, recording::kWeatherFormat.header};
  std::unique_ptr<recording::FlacScratch> flac_scratch_;  // one for every sensor: one thread writes
  std::vector<std::unique_ptr<FlacStream>> flac_;
  std::array<FlacStream*, 256> flac_by_sensor_{};
  std::string folder_;  // full path of the open segment; empty when none
  CaptureTime segment_start_{}, last_flush_{}, last_sync_{}, last_retry_{};
  bool want_segment_ = true;
  std::deque<std::pair<std::string, std::uint64_t>> closed_;  // older segments, oldest first, with bytes
  std::uint64_t sequence_ = 0;
  recording::LineBuilder line_;
  RecorderStatus status_;
};

}  // namespace roadload::firmware
