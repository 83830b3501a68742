#include "roadload/firmware/recorder.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <random>
#include <system_error>

#include "roadload/recording/candump.hpp"
#include "roadload/recording/flac_accel.hpp"

namespace roadload::firmware {

namespace fs = std::filesystem;

namespace {

constexpr Nanoseconds kFlushPeriod{250'000'000};
constexpr Nanoseconds kRetryPeriod{1'000'000'000};
constexpr std::size_t kSequenceDigits = 6;

// "000042-20261122T054012Z": the sequence orders segments even when the wall clock is wrong.
std::string segment_name(std::uint64_t sequence) {
  char stamp[32] = "unknown-time";
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  if (gmtime_r(&now, &utc) != nullptr) std::strftime(stamp, sizeof stamp, "%Y%m%dT%H%M%SZ", &utc);
  char name[64];
  std::snprintf(name, sizeof name, "%0*llu-%s", static_cast<int>(kSequenceDigits), static_cast<unsigned long long>(sequence), stamp);
  return name;
}

std::uint64_t sequence_of(const std::string& name) {
  if (name.size() <= kSequenceDigits || name[kSequenceDigits] != '-') return 0;
  std::uint64_t v = 0;
  for (std::size_t i = 0; i < kSequenceDigits; ++i) {
    if (name[i] < '0' || name[i] > '9') return 0;
    v = v * 10 + static_cast<std::uint64_t>(name[i] - '0');
  }
  return v;
}

std::uint64_t folder_bytes(const fs::path& dir) {
  std::uint64_t total = 0;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(dir, ec)) {
    std::error_code size_ec;
    const auto size = e.file_size(size_ec);
    if (!size_ec) total += size;
  }
  return total;
}

bool write_whole_file(const std::string& path, const std::string& text) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0640);
  if (fd < 0) return false;
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t n = ::write(fd, text.data() + done, text.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      const int err = n < 0 ? errno : ENOSPC;
      ::close(fd);
      errno = err;
      return false;
    }
    done += static_cast<std::size_t>(n);
  }
  const bool ok = fdatasync(fd) == 0;
  const int err = errno;
  ::close(fd);
  errno = err;
  return ok;
}

// A run's id: 64 random bits from the kernel's pool, so two gateways (or two runs of one) never
// share it and their segments are never joined into one drive.
std::string new_recording_id() {
  std::random_device entropy;
  const std::uint64_t id = (static_cast<std::uint64_t>(entropy()) << 32) | entropy();
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(id));
  return text;
}

}  // namespace

Recorder::Recorder(RecorderConfig config, recording::Metadata meta, std::vector<std::string> interfaces)
    : config_(std::move(config)), meta_(std::move(meta)), interfaces_(std::move(interfaces)) {
  if (config_.compression_level > 0)
    compressor_ = std::make_unique<FrameCompressor>(config_.compression_level, AppendFile::kBufferBytes);
  if (!config_.accel_flac.empty()) flac_scratch_ = std::make_unique<recording::FlacScratch>();
  for (const AccelFlacSensor& a : config_.accel_flac) {
    auto f = std::make_unique<FlacStream>();
    f->sensor = a;
    f->encoder = std::make_unique<recording::FlacEncoder>(*flac_scratch_);
    flac_by_sensor_[a.sensor] = f.get();
    flac_.push_back(std::move(f));
  }
  meta_.recording_id = new_recording_id();
  meta_.segment = 0;
  scan_data_dir();
}

Recorder::~Recorder() { end_segment(); }

void Recorder::scan_data_dir() {
  std::error_code ec;
  std::vector<std::pair<std::string, std::uint64_t>> found;
  for (const auto& e : fs::directory_iterator(config_.data_dir, ec)) {
    const std::string name = e.path().filename().string();
    const std::uint64_t seq = sequence_of(name);
    if (seq == 0 || !e.is_directory()) continue;
    sequence_ = std::max(sequence_, seq);
    found.emplace_back(name, folder_bytes(e.path()));
  }
  std::sort(found.begin(), found.end());
  closed_.assign(found.begin(), found.end());
}

void Recorder::note_error(const std::string& what, int err) {
  status_.error = err;
  status_.error_text = what + ": " + std::strerror(err);
}

bool Recorder::start_segment(CaptureTime now) {
  last_retry_ = now;
  std::error_code ec;
  fs::create_directories(config_.data_dir, ec);
  if (ec) {
    note_error(config_.data_dir, ec.value());
    return false;
  }
  const std::string name = segment_name(sequence_ + 1);
  const std::string folder = config_.data_dir + "/" + name;
  if (!fs::create_directory(folder, ec) && ec) {
    note_error(folder, ec.value());
    return false;
  }
  ++meta_.segment;
  if (!write_whole_file(folder + "/" + recording::kMetaFile, recording::format_metadata(meta_))) {
    note_error(folder + "/meta.toml", errno);
    fs::remove_all(folder, ec);
    --meta_.segment;
    return false;
  }
  ++sequence_;
  ++status_.segments;
  folder_ = folder;
  status_.segment = name;
  segment_start_ = now;
  last_flush_ = last_sync_ = now;
  want_segment_ = false;
  return true;
}

void Recorder::append(Stream& s, std::string_view line) {
  if (folder_.empty()) {
    ++status_.lines_lost;
    return;
  }
  if (!s.file.is_open()) {
    const std::string path = folder_ + "/" + s.name + (compressor_ ? recording::kCompressedSuffix : "");
    if (!s.file.open(path, compressor_.get())) {
      note_error(path, s.file.last_errno());
      ++status_.lines_lost;
      return;
    }
    if (!s.header.empty()) s.file.append(s.header);
  }
  if (s.file.append(line)) {
    ++status_.lines;
  } else {
    ++status_.lines_lost;
  }
}

void Recorder::write(const CanFrame& f) {
  char buf[recording::kMaxLineChars + 1];
  const std::string_view iface = f.iface < interfaces_.size() ? std::string_view(interfaces_[f.iface]) : "can?";
  const std::size_t n = recording::format_candump_line(f, iface, buf);
  buf[n] = '\n';
  append(can_, {buf, n + 1});
}

void Recorder::write(const AccelSample& s) {
  if (FlacStream* f = flac_by_sensor_[s.sensor]) return write_flac(*f, s);
  append(accel_, recording::format_row(s, line_));
}

void Recorder::write_flac(FlacStream& f, const AccelSample& s) {
  const auto row = recording::accel_flac_row(s, f.sensor.step_mps2);
  if (!row || folder_.empty()) {
    // A value off the sensor's steps cannot be stored as counts: counted, as a line that did not fit.
    ++status_.lines_lost;
    return;
  }
  if (!f.file.is_open()) {
    const std::string path = folder_ + "/" + recording::accel_flac_file(f.sensor.sensor);
    if (!f.file.open(path)) {
      note_error(path, f.file.last_errno());
      ++status_.lines_lost;
      return;
    }
    const auto header = recording::start_accel_flac(*f.encoder, f.sensor.sensor, f.sensor.rate_hz, f.sensor.step_mps2);
    put(f, header, f.encoder->samples_written());
  }
  const std::uint64_t before = f.encoder->samples_written();
  put(f, f.encoder->push(*row), before);
  ++status_.lines;
}

void Recorder::put(FlacStream& f, std::span<const std::uint8_t> bytes, std::uint64_t samples_before) {
  if (bytes.empty()) return;
  if (!f.file.append({reinterpret_cast<const char*>(bytes.data()), bytes.size()})) {
    status_.lines_lost += f.encoder->samples_written() - samples_before;
  }
}

bool Recorder::flush_file(AppendFile& file, bool sync) {
  if (!file.is_open() || (sync ? file.sync() : file.flush())) return true;
  note_error(file.path(), file.last_errno());
  return false;
}
void Recorder::write(const GnssFix& s) { append(gnss_, recording::format_row(s, line_)); }
void Recorder::write(const WeatherSample& s) { append(weather_, recording::format_row(s, line_)); }

std::uint64_t Recorder::segment_bytes() const {
  std::uint64_t total = 0;
  for (const Stream* s : {&can_, &accel_, &gnss_, &weather_}) total += s->file.bytes();
  for (const auto& f : flac_) total += f->file.bytes();
  return total;
}

void Recorder::tick(CaptureTime now) {
  if (folder_.empty()) {
    if (want_segment_ || now - last_retry_ >= kRetryPeriod) start_segment(now);
    if (folder_.empty()) return;
  }
  const bool sync = now - last_sync_ >= config_.fsync_interval;
  if (sync || now - last_flush_ >= kFlushPeriod) {
    bool ok = true;
    for (Stream* s : {&can_, &accel_, &gnss_, &weather_}) ok = flush_file(s->file, sync) && ok;
    for (const auto& f : flac_) {
      // The open block becomes a frame at each fsync, as the zstd streams' frames do.
      if (sync && f->file.is_open()) {
        const std::uint64_t before = f->encoder->samples_written();
        put(*f, f->encoder->close_frame(), before);
      }
      ok = flush_file(f->file, sync) && ok;
    }
    if (ok && status_.error != 0) {
      status_.error = 0;
      status_.error_text.clear();
    }
    last_flush_ = now;
    if (sync) last_sync_ = now;
  }
  if (now - segment_start_ >= config_.segment_max || segment_bytes() >= config_.segment_max_bytes) {
    end_segment();
    start_segment(now);
  }
  keep_quota();
}

void Recorder::end_segment() {
  if (folder_.empty()) return;
  for (Stream* s : {&can_, &accel_, &gnss_, &weather_}) {
    if (!s->file.is_open()) continue;
    const std::uint64_t before = s->file.lines_lost();
    if (!s->file.close()) note_error(s->file.path(), s->file.last_errno());
    status_.lines_lost += s->file.lines_lost() - before;
  }
  for (const auto& f : flac_) {
    if (!f->file.is_open()) continue;
    const std::uint64_t before = f->encoder->samples_written();
    put(*f, f->encoder->close_frame(true), before);
    if (!f->file.close()) note_error(f->file.path(), f->file.last_errno());
  }
  closed_.emplace_back(status_.segment, folder_bytes(folder_));
  folder_.clear();
  status_.segment.clear();
  want_segment_ = true;
}

void Recorder::keep_quota() {
  std::uint64_t total = segment_bytes();
  for (const auto& c : closed_) total += c.second;
  while (total > config_.quota_bytes && !closed_.empty()) {
    std::error_code ec;
    fs::remove_all(config_.data_dir + "/" + closed_.front().first, ec);
    total -= closed_.front().second;
    closed_.pop_front();
    ++status_.segments_deleted;
  }
  status_.bytes_in_dir = total;
}

}  // namespace roadload::firmware
