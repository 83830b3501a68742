#include <algorithm>
#include <array>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <string_view>

#include "roadload/recording/flac_accel.hpp"
#include "roadload/recording/flac_encoder.hpp"

namespace roadload::recording {
namespace {

constexpr std::int64_t kMaxStampS = 0x7FFFFFFF;

void put(OutputFile& file, std::span<const std::uint8_t> bytes) {
  file.write({reinterpret_cast<const char*>(bytes.data()), bytes.size()});
}

}  // namespace

std::string accel_flac_file(std::uint8_t sensor) { return "accel-" + std::to_string(sensor) + ".flac"; }

std::optional<std::uint8_t> accel_flac_sensor(const std::string& file_name) {
  const std::string_view n(file_name);
  constexpr std::string_view prefix = "accel-", suffix = ".flac";
  if (!n.starts_with(prefix) || !n.ends_with(suffix) || n.size() <= prefix.size() + suffix.size()) return std::nullopt;
  const std::string_view digits = n.substr(prefix.size(), n.size() - prefix.size() - suffix.size());
  unsigned id = 0;
  const auto r = std::from_chars(digits.data(), digits.data() + digits.size(), id);
  if (r.ec != std::errc{} || r.ptr != digits.data() + digits.size() || id > 255) return std::nullopt;
  if (digits.size() > 1 && digits[0] == '0') return std::nullopt;  // one name per sensor
  return static_cast<std::uint8_t>(id);
}

std::optional<std::array<std::int32_t, 5>> accel_flac_row(const AccelSample& s, double step_mps2, const char** bad) {
  const std::int64_t t_ns = s.t.time_since_epoch().count();
  auto refuse = [&](const char* field) {
    if (bad != nullptr) *bad = field;
    return std::nullopt;
  };
  if (t_ns < 0 || t_ns / kNsPerS > kMaxStampS) return refuse("t_ns");
  std::array<std::int32_t, 5> row{};
  const std::array<double, 3> v{s.x_mps2, s.y_mps2, s.z_mps2};
  static constexpr std::array<const char*, 3> kAxis{"x", "y", "z"};
  for (std::size_t a = 0; a < 3; ++a) {
    const double count = std::round(v[a] / step_mps2);
    // The stored value is count x step: it must give back the very same double.
    if (!(std::abs(count) < 0x7FFFFFFF) || count * step_mps2 != v[a]) return refuse(kAxis[a]);
    row[a] = static_cast<std::int32_t>(count);
  }
  row[3] = static_cast<std::int32_t>(t_ns / kNsPerS);
  row[4] = static_cast<std::int32_t>(t_ns % kNsPerS);
  return row;
}

std::span<const std::uint8_t> start_accel_flac(FlacEncoder& encoder, std::uint8_t sensor, double rate_hz, double step_mps2) {
  std::array<char, 64> step{};
  std::snprintf(step.data(), step.size(), "%.17g", step_mps2);
  const std::string sensor_entry = "ROADLOAD_SENSOR=" + std::to_string(sensor);
  const std::string step_entry = std::string("ROADLOAD_STEP_MPS2=") + step.data();
  const std::array<std::string_view, 3> comments{"ROADLOAD_LAYOUT=accel x,y,z counts; stamp s, ns", sensor_entry, step_entry};
  const auto rate = static_cast<std::uint32_t>(std::clamp(std::lround(rate_hz), 1L, 655350L));
  return encoder.start(5, rate, comments);
}

AccelFlacWriter::AccelFlacWriter(AccelFlacWriter&&) noexcept = default;
AccelFlacWriter& AccelFlacWriter::operator=(AccelFlacWriter&&) noexcept = default;
AccelFlacWriter::~AccelFlacWriter() { close(); }

Parsed<AccelFlacWriter> AccelFlacWriter::create(const std::string& path, std::uint8_t sensor, double rate_hz, double step_mps2) {
  if (!(step_mps2 > 0) || !std::isfinite(step_mps2)) return ParseError{path, 0, "step", "must be a positive number"};
  auto file = OutputFile::create(path);
  if (!file) return file.error();
  AccelFlacWriter w;
  w.file_ = std::move(file.value());
  w.step_mps2_ = step_mps2;
  w.scratch_ = std::make_unique<FlacScratch>();
  w.encoder_ = std::make_unique<FlacEncoder>(*w.scratch_);
  put(w.file_, start_accel_flac(*w.encoder_, sensor, rate_hz, step_mps2));
  return w;
}

std::optional<ParseError> AccelFlacWriter::write(const AccelSample& s) {
  const char* bad = nullptr;
  const auto row = accel_flac_row(s, step_mps2_, &bad);
  if (!row) {
    const bool stamp = std::string_view(bad) == "t_ns";
    return ParseError{file_.path(), 0, "sample " + std::to_string(samples_ + 1) + " " + bad,
                      stamp ? "outside 0 .. 2^31 s" : "not a whole number of the sensor's step"};
  }
  put(file_, encoder_->push(*row));
  ++samples_;
  return std::nullopt;
}

std::optional<ParseError> AccelFlacWriter::close() {
  if (!file_.is_open()) return std::nullopt;
  put(file_, encoder_->close_frame(true));
  return file_.close();
}

}  // namespace roadload::recording
