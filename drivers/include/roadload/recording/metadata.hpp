#pragma once
// meta.toml of a recording: what was recorded, with what, and on which clock. It never says which
// simulator effects were on; that lives only in a simulation's ground truth.
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "roadload/parse_error.hpp"
#include "roadload/vehicle.hpp"

namespace roadload::recording {

inline constexpr std::int64_t kFormatVersion = 1;

// The files of a recording folder (docs/recording-format.md).
inline constexpr const char* kCanFile = "can.log";
inline constexpr const char* kAccelFile = "accel.csv";
inline constexpr const char* kGnssFile = "gnss.csv";
inline constexpr const char* kWeatherFile = "weather.csv";
inline constexpr const char* kMetaFile = "meta.toml";
// A stream may be stored compressed, as roadloadd writes it: its name and this suffix.
inline constexpr const char* kCompressedSuffix = ".zst";

struct SensorInfo {
  std::int64_t id = 0;   // the `sensor` column of accel.csv
  std::string name;      // e.g. TLF1, as the report labels its accelerometers
  std::string kind;      // "accelerometer", "gnss", "weather", "anemometer"
  std::string position;  // e.g. "tractor-front-axle-left"
  std::string part;      // e.g. "ADXL355"
  double rate_hz = 0.0;
};

struct Metadata {
  std::int64_t version = kFormatVersion;
  std::string created_by;  // program and version that wrote it
  // One run of a logger that cuts its drive into segments: every segment carries the run's id and
  // its place in it (1, 2, ...), so a reader can join them back into one drive. Empty / 0: a
  // recording of one piece.
  std::string recording_id;
  std::int64_t segment = 0;
  std::string clock_source;                         // where capture stamps came from: "kernel", "simulated", ...
  std::optional<std::int64_t> utc_offset_ns;        // UTC = capture + offset, when a GNSS fix gave one
  std::map<std::string, std::string> vehicle_text;  // vin, name, ...
  std::map<std::string, double> vehicle;            // mass_kg, ... (names carry units)
  // The vehicle file the recording was made with, in full ([vehicle.file]); the keys above state
  // this drive's own values over it (its cargo, its antenna).
  std::optional<Vehicle> vehicle_file;
  std::vector<std::string> can_interfaces;
  std::vector<SensorInfo> sensors;
};

Parsed<Metadata> parse_metadata(std::string_view text, std::string_view source);
std::string format_metadata(const Metadata& m);

}  // namespace roadload::recording
