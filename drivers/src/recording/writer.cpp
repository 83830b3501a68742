#include "roadload/recording/writer.hpp"

#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <utility>

#include "roadload/recording/candump.hpp"
#include "roadload/recording/flac_accel.hpp"

namespace roadload::recording {

OutputFile::OutputFile(OutputFile&& o) noexcept
    : file_(std::exchange(o.file_, nullptr)), path_(std::move(o.path_)), lines_(o.lines_), errno_(o.errno_) {}

OutputFile& OutputFile::operator=(OutputFile&& o) noexcept {
  if (this != &o) {
    close();
    file_ = std::exchange(o.file_, nullptr);
    path_ = std::move(o.path_);
    lines_ = o.lines_;
    errno_ = o.errno_;
  }
  return *this;
}

OutputFile::~OutputFile() { close(); }

Parsed<OutputFile> OutputFile::create(std::string path) {
  OutputFile f;
  f.file_ = std::fopen(path.c_str(), "w");
  if (!f.file_) return ParseError{path, 0, "file", std::strerror(errno)};
  // Large buffer: a one-hour simulated drive writes gigabytes of accelerometer lines.
  std::setvbuf(f.file_, nullptr, _IOFBF, 1 << 20);
  f.path_ = std::move(path);
  return f;
}

void OutputFile::write(std::string_view text) {
  if (!file_ || errno_ != 0 || text.empty()) return;
  if (std::fwrite(text.data(), 1, text.size(), file_) != text.size()) errno_ = errno ? errno : EIO;
  ++lines_;
}

std::optional<ParseError> OutputFile::close() {
  if (!file_) return std::nullopt;
  if (std::fclose(std::exchange(file_, nullptr)) != 0 && errno_ == 0) errno_ = errno ? errno : EIO;
  if (errno_ == 0) return std::nullopt;
  return ParseError{path_, lines_, "write", std::strerror(errno_)};
}

LineBuilder& LineBuilder::num(std::int64_t v) {
  const auto r = std::to_chars(buf_ + len_, buf_ + sizeof buf_ - 1, v);
  if (r.ec == std::errc{}) len_ = static_cast<std::size_t>(r.ptr - buf_);
  return *this;
}

LineBuilder& LineBuilder::num(double v, int decimals) {
  if (std::isnan(v)) return *this;
  // Avoid "-0.000": it reads back equal, but a diff of two recordings would flag it.
  static constexpr double kHalfStep[] = {0.5, 0.05, 5e-3, 5e-4, 5e-5, 5e-6, 5e-7, 5e-8, 5e-9, 5e-10};
  if (decimals >= 0 && decimals < 10 && std::abs(v) < kHalfStep[decimals]) v = 0.0;
  // One byte stays free for finish()'s newline; a number that does not fit is left out whole.
  const auto r = std::to_chars(buf_ + len_, buf_ + sizeof buf_ - 1, v, std::chars_format::fixed, decimals);
  if (r.ec == std::errc{}) len_ = static_cast<std::size_t>(r.ptr - buf_);
  return *this;
}

LineBuilder& LineBuilder::text(std::string_view s) {
  const std::size_t n = std::min(s.size(), sizeof buf_ - 1 - len_);
  std::memcpy(buf_ + len_, s.data(), n);
  len_ += n;
  return *this;
}

LineBuilder& LineBuilder::field(std::string_view s) {
  if (s.find_first_of(",\"\r\n") == std::string_view::npos) return text(s);
  text("\"");
  for (std::size_t at = 0; at < s.size();) {
    const std::size_t quote = s.find('"', at);
    text(s.substr(at, quote == std::string_view::npos ? std::string_view::npos : quote + 1 - at));
    if (quote == std::string_view::npos) break;
    text("\"");
    at = quote + 1;
  }
  return text("\"");
}

std::string_view LineBuilder::finish() {
  buf_[len_++] = '\n';
  return {buf_, len_};
}

Parsed<RecordingWriter> RecordingWriter::create(const std::string& folder, const Metadata& meta) {
  std::error_code ec;
  std::filesystem::create_directories(folder, ec);
  if (ec) return ParseError{folder, 0, "folder", ec.message()};
  auto m = OutputFile::create(folder + "/" + kMetaFile);
  if (!m) return m.error();
  m.value().write(format_metadata(meta));
  if (auto e = m.value().close()) return *e;
  return RecordingWriter(folder);
}

OutputFile& RecordingWriter::stream(OutputFile& f, const CsvStreamFormat& format) {
  if (f.is_open() || error_) return f;
  auto opened = OutputFile::create(folder_ + "/" + format.file);
  if (!opened) {
    error_ = opened.error();
    return f;
  }
  f = std::move(opened.value());
  f.write(format.header);
  return f;
}

void RecordingWriter::write(const CanFrame& frame, std::string_view iface) {
  char buf[kMaxLineChars + 1];
  const std::size_t n = format_candump_line(frame, iface, buf);
  buf[n] = '\n';
  stream(can_, {kCanFile, {}}).write({buf, n + 1});
}

std::string_view format_row(const AccelSample& s, LineBuilder& line) {
  line.clear();
  line.num(to_ns(s.t)).sep().num(std::int64_t{s.sensor}).sep();
  line.num(s.x_mps2, 6).sep().num(s.y_mps2, 6).sep().num(s.z_mps2, 6);
  return line.finish();
}

std::string_view format_row(const GnssFix& s, LineBuilder& line) {
  line.clear();
  line.num(to_ns(s.t)).sep().num(s.utc_ns).sep().num(s.lat_deg, 9).sep().num(s.lon_deg, 9).sep();
  line.num(s.alt_m, 3).sep().num(s.speed_mps, 3).sep().num(s.course_deg, 2).sep();
  line.num(static_cast<std::int64_t>(s.mode)).sep().num(s.hdop, 1);
  return line.finish();
}

std::string_view format_row(const WeatherSample& s, LineBuilder& line) {
  line.clear();
  line.num(to_ns(s.t)).sep().num(std::int64_t{s.station}).sep().num(s.air_temp_c, 2).sep();
  line.num(s.pressure_pa, 1).sep().num(s.wind_speed_mps, 2).sep().num(s.wind_from_deg, 1);
  return line.finish();
}

RecordingWriter::RecordingWriter(std::string folder) : folder_(std::move(folder)) {}
RecordingWriter::RecordingWriter(RecordingWriter&&) noexcept = default;
RecordingWriter& RecordingWriter::operator=(RecordingWriter&&) noexcept = default;
RecordingWriter::~RecordingWriter() = default;

std::optional<ParseError> RecordingWriter::accel_as_flac(std::uint8_t sensor, double rate_hz, double step_mps2) {
  auto w = AccelFlacWriter::create(folder_ + "/" + accel_flac_file(sensor), sensor, rate_hz, step_mps2);
  if (!w) return w.error();
  flac_[sensor] = std::make_unique<AccelFlacWriter>(std::move(w.value()));
  return std::nullopt;
}

void RecordingWriter::write(const AccelSample& s) {
  if (AccelFlacWriter* f = flac_[s.sensor].get()) {
    if (auto e = f->write(s); e && !error_) error_ = e;
    return;
  }
  stream(accel_, kAccelFormat).write(format_row(s, line_));
}

void RecordingWriter::write(const GnssFix& s) { stream(gnss_, kGnssFormat).write(format_row(s, line_)); }

void RecordingWriter::write(const WeatherSample& s) { stream(weather_, kWeatherFormat).write(format_row(s, line_)); }

std::optional<ParseError> RecordingWriter::close() {
  for (OutputFile* f : {&can_, &accel_, &gnss_, &weather_}) {
    if (auto e = f->close(); e && !error_) error_ = e;
  }
  for (auto& f : flac_) {
    if (!f) continue;
    if (auto e = f->close(); e && !error_) error_ = e;
  }
  return error_;
}

}  // namespace roadload::recording
