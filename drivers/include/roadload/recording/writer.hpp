#pragma once
// Writes a recording folder (docs/recording-format.md): meta.toml, can.log and the CSV streams.
// Streams are created on first use, so a recording holds only what was recorded.
#include <array>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "roadload/can_frame.hpp"
#include "roadload/parse_error.hpp"
#include "roadload/recording/metadata.hpp"
#include "roadload/samples.hpp"

namespace roadload::recording {

class AccelFlacWriter;

// A buffered output file that remembers its first error instead of throwing.
class OutputFile {
 public:
  OutputFile() = default;
  OutputFile(const OutputFile&) = delete;
  OutputFile& operator=(const OutputFile&) = delete;
  OutputFile(OutputFile&& o) noexcept;
  OutputFile& operator=(OutputFile&& o) noexcept;
  ~OutputFile();

  static Parsed<OutputFile> create(std::string path);
  void write(std::string_view text);
  long lines() const { return lines_; }
  const std::string& path() const { return path_; }
  // Flushes and closes; the first write or close error, naming the file and the line reached.
  std::optional<ParseError> close();
  bool is_open() const { return file_ != nullptr; }

 private:
  std::FILE* file_ = nullptr;
  std::string path_;
  long lines_ = 0;
  int errno_ = 0;
};

// Appends fixed-point numbers to a line without locale or allocation.
class LineBuilder {
 public:
  LineBuilder& num(std::int64_t v);
  LineBuilder& num(double v, int decimals);  // NaN gives an empty field
  LineBuilder& text(std::string_view s);
  // A text field as RFC 4180 writes it: in quotes, its quotes doubled, when it holds a comma, a
  // quote or a line break.
  LineBuilder& field(std::string_view s);
  LineBuilder& sep() { return text(","); }
  std::string_view finish();  // appends '\n'; the view lives until the next clear()
  void clear() { len_ = 0; }

 private:
  char buf_[4096];
  std::size_t len_ = 0;
};

// The CSV streams' files, headers and rows, shared by every writer of recordings.
struct CsvStreamFormat {
  const char* file;
  std::string_view header;  // with its newline
};
inline constexpr CsvStreamFormat kAccelFormat{kAccelFile, "t_ns,sensor,x_mps2,y_mps2,z_mps2\n"};
inline constexpr CsvStreamFormat kGnssFormat{kGnssFile, "t_ns,utc_ns,lat_deg,lon_deg,alt_m,speed_mps,course_deg,mode,hdop\n"};
inline constexpr CsvStreamFormat kWeatherFormat{kWeatherFile, "t_ns,station,air_temp_c,pressure_pa,wind_speed_mps,wind_from_deg\n"};
// Each returns the row with its newline; the view lives until `line` is next cleared.
std::string_view format_row(const AccelSample& s, LineBuilder& line);
std::string_view format_row(const GnssFix& s, LineBuilder& line);
std::string_view format_row(const WeatherSample& s, LineBuilder& line);

class RecordingWriter {
 public:
  static Parsed<RecordingWriter> create(const std::string& folder, const Metadata& meta);
  RecordingWriter(RecordingWriter&&) noexcept;
  RecordingWriter& operator=(RecordingWriter&&) noexcept;
  ~RecordingWriter();

  // From now on `sensor`'s samples go to its FLAC file (recording/flac_accel.hpp), not accel.csv.
  std::optional<ParseError> accel_as_flac(std::uint8_t sensor, double rate_hz, double step_mps2);

  void write(const CanFrame& f, std::string_view iface);
  void write(const AccelSample& s);
  void write(const GnssFix& s);
  void write(const WeatherSample& s);
  std::optional<ParseError> close();

 private:
  explicit RecordingWriter(std::string folder);
  OutputFile& stream(OutputFile& f, const CsvStreamFormat& format);

  std::string folder_;
  OutputFile can_, accel_, gnss_, weather_;
  std::array<std::unique_ptr<AccelFlacWriter>, 256> flac_;
  std::optional<ParseError> error_;
  LineBuilder line_;
};

}  // namespace roadload::recording
