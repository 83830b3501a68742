#include "roadload/recording/reader.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "roadload/merge.hpp"
#include "roadload/recording/csv.hpp"
#include "roadload/recording/flac_accel.hpp"

namespace roadload::recording {
namespace {

namespace fs = std::filesystem;

// Reads a CSV stream whose rows map to one sample type. `Row` converts fields into the sample
// and names the first bad field.
template <typename Sample, typename Convert>
class CsvStream final : public Stream {
 public:
  CsvStream(CsvReader csv, const char* name, Convert convert) : csv_(std::move(csv)), name_(name), convert_(convert) {}

  bool next(Record& out, ErrorLog& errors) override {
    std::span<const std::string_view> row;
    for (;;) {
      const CsvReader::Status st = csv_.next(row);
      if (st == CsvReader::Status::end) {
        if (csv_.error()) errors.add(*csv_.error());
        return false;
      }
      if (st == CsvReader::Status::bad_row) {
        errors.add(*csv_.error());
        continue;
      }
      Sample s;
      if (auto bad = convert_(row, s)) {
        errors.add(csv_.field_error(bad->first, bad->second));
        continue;
      }
      count(s.t);
      out = s;
      return true;
    }
  }
  const char* name() const override { return name_; }

 private:
  CsvReader csv_;
  const char* name_;
  Convert convert_;
};

using FieldError = std::optional<std::pair<std::size_t, std::string>>;

// Reads numeric fields in order, remembering the first that does not parse.
class Fields {
 public:
  explicit Fields(std::span<const std::string_view> row) : row_(row) {}
  std::int64_t i64(std::size_t i) {
    if (auto v = parse_i64(row_[i])) return *v;
    fail(i, "expected an integer");
    return 0;
  }
  // A capture-clock stamp as can.log bounds it: nanoseconds from 0 to 9e18 (year 2255 as UNIX time).
  CaptureTime stamp(std::size_t i) {
    const std::int64_t ns = i64(i);
    if (ns < 0 || ns > kMaxStampNs) fail(i, "stamp out of range 0..9000000000000000000 ns");
    return capture_time_from_ns(ns);
  }
  // UTC in ns since 1970 when given; an empty field is a receiver that does not say (0).
  std::int64_t utc_or_zero(std::size_t i) {
    if (row_[i].empty()) return 0;
    const std::int64_t ns = i64(i);
    if (ns < 0 || ns > kMaxStampNs) fail(i, "UTC out of range 0..9000000000000000000 ns");
    return ns;
  }
  double f64(std::size_t i) {
    if (auto v = parse_f64(row_[i])) return *v;
    fail(i, "expected a finite number");
    return 0.0;
  }
  // An empty field is a quantity this sensor does not measure (an anemometer has no barometer).
  double f64_or_nan(std::size_t i) {
    if (row_[i].empty()) return std::numeric_limits<double>::quiet_NaN();
    return f64(i);
  }
  std::uint8_t small(std::size_t i, std::int64_t max) {
    const std::int64_t v = i64(i);
    if (v < 0 || v > max) fail(i, "out of range 0.." + std::to_string(max));
    return static_cast<std::uint8_t>(v);
  }
  // A value a sensor can report: within [lo, hi] (NaN, an unmeasured quantity, passes).
  void within(std::size_t i, double v, double lo, double hi, const char* what) {
    if (v < lo || v > hi) fail(i, std::string(what) + " out of range " + range(lo, hi));
  }
  FieldError error() const { return error_; }

 private:
  static std::string range(double lo, double hi) {
    char text[64];
    std::snprintf(text, sizeof text, "%g..%g", lo, hi);
    return text;
  }
  void fail(std::size_t i, std::string m) {
    if (!error_) error_.emplace(i, std::move(m));
  }
  static constexpr std::int64_t kMaxStampNs = 9'000'000'000'000'000'000;
  std::span<const std::string_view> row_;
  FieldError error_;
};

constexpr std::string_view kAccelColumns[] = {"t_ns", "sensor", "x_mps2", "y_mps2", "z_mps2"};
// Many receivers and loggers give neither UTC nor course: those columns may be left out.
constexpr std::string_view kGnssColumns[] = {"t_ns", "lat_deg", "lon_deg", "alt_m", "speed_mps", "mode"};
constexpr std::string_view kGnssOptional[] = {"utc_ns", "course_deg", "hdop"};
constexpr std::string_view kWeatherColumns[] = {"t_ns", "station", "air_temp_c", "pressure_pa", "wind_speed_mps", "wind_from_deg"};

FieldError to_accel(std::span<const std::string_view> row, AccelSample& s) {
  Fields f(row);
  s.t = f.stamp(0);
  s.sensor = f.small(1, 255);
  s.x_mps2 = f.f64(2);
  s.y_mps2 = f.f64(3);
  s.z_mps2 = f.f64(4);
  // 200 g: beyond any accelerometer on a truck (shock sensors included).
  f.within(2, s.x_mps2, -kMaxAccelMps2, kMaxAccelMps2, "acceleration");
  f.within(3, s.y_mps2, -kMaxAccelMps2, kMaxAccelMps2, "acceleration");
  f.within(4, s.z_mps2, -kMaxAccelMps2, kMaxAccelMps2, "acceleration");
  return f.error();
}

FieldError to_gnss(std::span<const std::string_view> row, GnssFix& s) {
  Fields f(row);
  s.t = f.stamp(0);
  s.lat_deg = f.f64(1);
  s.lon_deg = f.f64(2);
  s.alt_m = f.f64(3);
  s.speed_mps = f.f64(4);
  s.mode = static_cast<GnssFixMode>(f.small(5, 5));
  s.utc_ns = f.utc_or_zero(6);
  s.course_deg = f.f64_or_nan(7);
  s.hdop = f.f64_or_nan(8);  // gpsd reports HDOP only with satellites in view
  f.within(1, s.lat_deg, -90, 90, "latitude");
  f.within(2, s.lon_deg, -180, 180, "longitude");
  f.within(3, s.alt_m, -1000, 10000, "height");
  f.within(4, s.speed_mps, 0, 150, "speed");
  f.within(7, s.course_deg, 0, 360, "course");
  f.within(8, s.hdop, 0, 100, "HDOP");
  return f.error();
}

FieldError to_weather(std::span<const std::string_view> row, WeatherSample& s) {
  Fields f(row);
  s.t = f.stamp(0);
  s.station = f.small(1, 255);
  s.air_temp_c = f.f64_or_nan(2);
  s.pressure_pa = f.f64_or_nan(3);
  s.wind_speed_mps = f.f64_or_nan(4);
  s.wind_from_deg = f.f64_or_nan(5);
  // Air that exists at a road: the coldest and hottest recorded, the pressures of any road's height.
  f.within(2, s.air_temp_c, -90, 60, "air temperature");
  f.within(3, s.pressure_pa, 30000, 110000, "pressure");
  f.within(4, s.wind_speed_mps, 0, 120, "wind speed");
  f.within(5, s.wind_from_deg, 0, 360, "wind direction");
  return f.error();
}

template <typename Sample, typename Convert>
Parsed<std::unique_ptr<Stream>> open_csv(const fs::path& path, std::span<const std::string_view> cols, const char* name,
                                         Convert convert, std::span<const std::string_view> optional = {}) {
  auto csv = CsvReader::open(path.string(), cols, optional);
  if (!csv) return csv.error();
  return std::unique_ptr<Stream>(new CsvStream<Sample, Convert>(std::move(csv.value()), name, convert));
}

}  // namespace

void ErrorLog::add(ParseError e) {
  ++count_;
  auto file = std::find_if(by_file_.begin(), by_file_.end(), [&](const auto& f) { return f.first == e.file; });
  if (file == by_file_.end()) file = by_file_.insert(by_file_.end(), {e.file, 0});
  ++file->second;
  if (kept_.size() < kMaxKept) kept_.push_back(std::move(e));
}

std::uint64_t ErrorLog::count_in(std::string_view name) const {
  std::uint64_t n = 0;
  for (const auto& [file, count] : by_file_) {
    std::string_view f(file);
    if (f.ends_with(kCompressedSuffix)) f.remove_suffix(std::string_view(kCompressedSuffix).size());
    n += f.ends_with(name) ? count : 0;
  }
  return n;
}

Parsed<std::unique_ptr<CandumpStream>> CandumpStream::open(const std::string& path, const InterfaceTable* interfaces) {
  auto lines = LineReader::open(path);
  if (!lines) return lines.error();
  std::unique_ptr<CandumpStream> s(new CandumpStream(std::move(lines.value())));
  if (interfaces != nullptr) s->ifaces_ = *interfaces;
  return s;
}

const char* stream_file(unsigned bit) {
  switch (bit) {
    case kCanStream: return kCanFile;
    case kAccelStream: return kAccelFile;
    case kGnssStream: return kGnssFile;
    default: return kWeatherFile;
  }
}

std::optional<fs::path> find_stream(const fs::path& dir, const char* name) {
  std::error_code ec;
  fs::path p = dir / name;
  if (fs::exists(p, ec)) return p;
  p += kCompressedSuffix;
  if (fs::exists(p, ec)) return p;
  return std::nullopt;
}

std::string no_streams(unsigned streams) {
  if ((streams & kAllStreams) == kAllStreams) return "not a recording: no can.log or sensor CSV";
  std::string names;
  for (unsigned bit : kStreamBits) {
    if ((streams & bit) == 0) continue;
    names += names.empty() ? "" : " or ";
    names += bit == kAccelStream ? "accel.csv or accel-ID.flac" : stream_file(bit);
  }
  return names.empty() ? "no stream asked for" : "no " + names;
}

bool has_stream(const fs::path& dir, unsigned bit) {
  return find_stream(dir, stream_file(bit)).has_value() || (bit == kAccelStream && !find_accel_flac(dir).empty());
}

Parsed<std::unique_ptr<Stream>> open_stream(unsigned bit, const std::filesystem::path& dir, const InterfaceTable* interfaces) {
  if (bit == kAccelStream) {
    if (auto flac = find_accel_flac(dir); !flac.empty()) {
      if (!find_stream(dir, kAccelFile)) return open_accel_flac(flac);
      auto text = open_csv<AccelSample>(find_stream(dir, kAccelFile).value(), kAccelColumns, kAccelFile, to_accel);
      if (!text) return text.error();
      return open_accel_flac(flac, std::move(text.value()));
    }
  }
  const fs::path p = find_stream(dir, stream_file(bit)).value_or(dir / stream_file(bit));
  switch (bit) {
    case kCanStream: {
      auto can = CandumpStream::open(p.string(), interfaces);
      if (!can) return can.error();
      return std::unique_ptr<Stream>(std::move(can.value()));
    }
    case kAccelStream: return open_csv<AccelSample>(p, kAccelColumns, kAccelFile, to_accel);
    case kGnssStream: return open_csv<GnssFix>(p, kGnssColumns, kGnssFile, to_gnss, kGnssOptional);
    default: return open_csv<WeatherSample>(p, kWeatherColumns, kWeatherFile, to_weather);
  }
}

bool CandumpStream::next_frame(CanFrame& out, ErrorLog& errors) {
  while (const auto line = lines_.next()) {
    if (lines_.overlong()) {
      errors.add(lines_.overlong_error());
      continue;
    }
    LineResult result;
    if (const auto e = parse_candump_line(*line, ifaces_, out, result)) {
      errors.add(ParseError{lines_.path(), lines_.line_number(), e->field, e->message});
      continue;
    }
    if (result == LineResult::ignored) {
      ++counts_.ignored_lines;
      continue;
    }
    count(out.t);
    return true;
  }
  if (lines_.error()) errors.add(*lines_.error());
  return false;
}

// Parsed in place: a frame copied into the record, line after line, cost 8 % of a decode.
bool CandumpStream::next(Record& out, ErrorLog& errors) {
  auto* f = std::get_if<CanFrame>(&out);
  return next_frame(f != nullptr ? *f : out.emplace<CanFrame>(), errors);
}

CaptureTime stamp_of(const Record& r) {
  return std::visit([](const auto& s) { return s.t; }, r);
}

Parsed<Metadata> read_metadata(const std::filesystem::path& dir) {
  const fs::path path = dir / kMetaFile;
  std::error_code ec;
  if (fs::is_directory(path, ec)) return ParseError{path.string(), 0, "", "Is a directory"};
  std::ifstream in(path);
  if (!in) return ParseError{path.string(), 0, "", "cannot be read"};
  std::stringstream text;
  text << in.rdbuf();
  return parse_metadata(text.str(), path.string());
}

Parsed<RecordingReader> RecordingReader::open(const std::string& path, unsigned streams) {
  RecordingReader r;
  std::error_code ec;
  if (!fs::is_directory(path, ec)) {
    auto can = CandumpStream::open(path);
    if (!can) return can.error();
    r.streams_.push_back(std::move(can.value()));
    return r;
  }
  const fs::path dir(path);
  if (fs::exists(dir / kMetaFile)) {
    auto meta = read_metadata(dir);
    if (!meta) return meta.error();
    r.meta_ = std::move(meta.value());
    r.has_meta_ = true;
  }
  for (unsigned bit : kStreamBits) {
    if ((streams & bit) == 0 || !has_stream(dir, bit)) continue;
    auto s = open_stream(bit, dir, nullptr);
    if (!s) return s.error();
    r.streams_.push_back(std::move(s.value()));
  }
  if (r.streams_.empty()) return ParseError{path, 0, "", no_streams(streams) + " in the folder"};
  return r;
}

const InterfaceTable& RecordingReader::interfaces() const {
  static const InterfaceTable kNone;
  for (const auto& s : streams_) {
    if (const InterfaceTable* t = s->interfaces()) return *t;
  }
  return kNone;
}

const Record* RecordingReader::next() {
  // One stream (a can.log, a folder of one) is already in its order: no heads to compare.
  if (streams_.size() == 1) return streams_[0]->next(current_, errors_) ? &current_ : nullptr;
  auto advance = [this](std::size_t i) {
    stamps_[i] = streams_[i]->next(heads_[i], errors_) ? stamp_of(heads_[i]) : CaptureTime::max();
  };
  if (!primed_) {
    heads_.resize(streams_.size());
    stamps_.resize(streams_.size());
    for (std::size_t i = 0; i < streams_.size(); ++i) advance(i);
    primed_ = true;
  } else if (has_taken_) {
    advance(taken_);
    // Only the stream taken has moved: while its head is older than every other, it is taken again
    // without comparing them all (eight accelerometer samples come for every other record).
    const CaptureTime t = stamps_[taken_];
    if (t != CaptureTime::max() && (t < rival_t_ || (t == rival_t_ && taken_ < rival_))) return &heads_[taken_];
  }
  const auto best = oldest_head(
      stamps_.size(), [this](std::size_t i) { return stamps_[i] != CaptureTime::max(); },
      [this](std::size_t i) { return stamps_[i]; });
  has_taken_ = best.has_value();
  taken_ = best.value_or(0);
  const auto rival = oldest_head(
      stamps_.size(), [this](std::size_t i) { return i != taken_ && stamps_[i] != CaptureTime::max(); },
      [this](std::size_t i) { return stamps_[i]; });
  rival_ = rival.value_or(stamps_.size());
  rival_t_ = rival ? stamps_[*rival] : CaptureTime::max();
  return has_taken_ ? &heads_[taken_] : nullptr;
}

bool RecordingReader::next_into(Record& out) {
  if (streams_.size() == 1) return streams_[0]->next(out, errors_);
  const Record* r = next();
  if (r != nullptr) out = *r;
  return r != nullptr;
}

}  // namespace roadload::recording
