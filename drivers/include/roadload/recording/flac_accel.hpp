#pragma once
// The accelerometers stored as FLAC (docs/recording-format.md): one file per sensor,
// accel-<sensor>.flac, five 32-bit channels at the sensor's nominal rate: the x, y and z counts as
// the part gives them, then the capture stamp as whole seconds and nanoseconds in the second. The
// value is count x ROADLOAD_STEP_MPS2 (a VORBIS_COMMENT), exactly what the driver or simulator
// produced. `flac -d --force-raw-format --endian=little --sign=signed` reads it back with any FLAC
// decoder; the text it stands for is 1/9 as large again in zstd (docs/journal.md, 2026-11-27).
#include <array>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "roadload/parse_error.hpp"
#include "roadload/recording/reader.hpp"
#include "roadload/recording/writer.hpp"
#include "roadload/samples.hpp"

namespace roadload::recording {

class FlacEncoder;
struct FlacScratch;

// "accel-3.flac", and whether a file name is one of them (its sensor id).
std::string accel_flac_file(std::uint8_t sensor);
std::optional<std::uint8_t> accel_flac_sensor(const std::string& file_name);
// The folder's accel-*.flac files, by sensor id.
std::vector<std::filesystem::path> find_accel_flac(const std::filesystem::path& dir);

// The five channels of one sample: nullopt when a value is not a whole number of `step_mps2` or
// the stamp lies outside 0 .. 2^31 s; `bad` then names the field ("x", "y", "z" or "t_ns").
std::optional<std::array<std::int32_t, 5>> accel_flac_row(const AccelSample& s, double step_mps2, const char** bad = nullptr);
// Starts `encoder` on one sensor's stream; returns the stream's header bytes.
std::span<const std::uint8_t> start_accel_flac(FlacEncoder& encoder, std::uint8_t sensor, double rate_hz, double step_mps2);

// What an accel-ID.flac file states of itself, to record a replay of it the same way.
struct AccelFlacInfo {
  std::uint8_t sensor = 0;
  double rate_hz = 0;  // STREAMINFO's, whole hertz
  double step_mps2 = 0;
};
Parsed<AccelFlacInfo> read_accel_flac_info(const std::filesystem::path& path);

// One sensor's samples into its FLAC file. A value that is not a whole number of steps cannot be
// stored without loss and is an error naming the sample; so is a stamp outside 0 .. 2^31 s.
class AccelFlacWriter {
 public:
  static Parsed<AccelFlacWriter> create(const std::string& path, std::uint8_t sensor, double rate_hz, double step_mps2);
  AccelFlacWriter(AccelFlacWriter&&) noexcept;
  AccelFlacWriter& operator=(AccelFlacWriter&&) noexcept;
  ~AccelFlacWriter();
  std::optional<ParseError> write(const AccelSample& s);
  // Writes the open block and closes the file.
  std::optional<ParseError> close();

 private:
  AccelFlacWriter() = default;
  std::unique_ptr<FlacScratch> scratch_;
  std::unique_ptr<FlacEncoder> encoder_;
  OutputFile file_;
  double step_mps2_ = 0;
  std::uint64_t samples_ = 0;
};

// Every sensor's file and, when given, accel.csv's stream, merged by stamp (a tie goes to accel.csv,
// then to the lower sensor id).
Parsed<std::unique_ptr<Stream>> open_accel_flac(const std::vector<std::filesystem::path>& files,
                                                std::unique_ptr<Stream> text = nullptr);

}  // namespace roadload::recording
