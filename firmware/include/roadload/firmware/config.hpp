#pragma once
// roadloadd's settings: built-in defaults, then config/roadloadd.toml (or --config), then the
// command line. Every default here is the one config/roadloadd.toml documents.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "roadload/parse_error.hpp"
#include "roadload/time.hpp"

namespace roadload::firmware {

struct CanBusConfig {
  std::string interface = "can0";
  bool j1939_only = true;        // 29-bit data frames and error frames
  double bitrate_bps = 500'000;  // for the bus load in the status
  std::int64_t receive_buffer_kib = 2048;
};

struct AccelConfig {
  std::uint8_t id = 0;     // accel.csv `sensor`
  std::string name;        // e.g. TLF1
  std::string position;    // e.g. tractor-front-axle-left
  std::string spidev;      // /dev/spidev0.0
  std::string gpiochip;    // gpiochip0
  std::uint32_t line = 0;  // data-ready line offset on the chip
  double range_g = 2;
  double odr_hz = 4000;
};

struct GnssConfig {
  bool enabled = true;
  std::string host = "localhost";
  std::string port = "2947";
};

struct RecordingConfig {
  bool enabled = true;
  std::string data_dir = "/var/lib/roadload";
  Seconds fsync_interval{1.0};
  Seconds segment_max{3600};
  double segment_max_mib = 512;
  double quota_mib = 8192;    // the oldest segments go first once the data dir holds more
  int compression_level = 1;  // zstd frames (1 is smaller and faster than 3 on these streams); 0: plain text
  // "flac": each accelerometer whose steps are known as accel-ID.flac (1/9 of accel.csv's bytes);
  // "text": every one in accel.csv.
  std::string accel_format = "flac";
};

struct StatusConfig {
  std::string text_file = "/var/log/roadload/status.log";
  std::string json_file = "/var/log/roadload/status.jsonl";  // empty: no JSON lines
  Seconds interval{1.0};
};

// Sensor streams from a recording instead of devices (`roadload replay` plays its CAN onto vcan).
struct ReplayConfig {
  std::string recording;    // empty: devices
  double rate = 1.0;        // 0: as fast as read
  bool can = false;         // CAN from the recording too, instead of the buses (benches, no vcan)
  std::string origin_file;  // written by `roadload replay --origin`: the timeline of the CAN it plays
};

// The truck the daemon rides in: its vehicle file (docs/vehicle-file.md), which the recordings carry
// in their meta.toml and the estimator models.
struct VehicleConfig {
  // A vehicle file or built-in name (config/vehicles). Empty: a replayed recording's own; otherwise
  // none, and the daemon records without estimating, as no truck is described.
  std::string file;
};

struct EstimatorConfig {
  std::string route;        // route file or built-in name; empty: no cells
  std::string results_dir;  // cells.csv and trip.json written here at exit; empty: none
  // The truck's calibration (`roadload calibrate`): its engine-loss table, and its CdA with the
  // standard error; empty or 0: EEC3's whole percent and the vehicle file's prior.
  std::string engine_losses;
  double cda_m2 = 0, cda_sigma_m2 = 0;
  double cda_torque_correlation = 0;  // between CdA's error and the flywheel torque's (calibrate --aero)
};

struct DaemonConfig {
  std::string source = "built-in defaults";  // where the settings came from
  std::vector<CanBusConfig> can{CanBusConfig{}};
  std::vector<AccelConfig> accelerometers;
  GnssConfig gnss;
  RecordingConfig recording;
  StatusConfig status;
  ReplayConfig replay;
  VehicleConfig vehicle;
  EstimatorConfig estimator;
};

Parsed<DaemonConfig> load_config(const std::string& path);
// Checks the values together (ranges, duplicate interfaces and ids); names the field.
std::optional<ParseError> validate(const DaemonConfig& c);
// The effective settings as TOML, for --print-config and the recording's provenance.
std::string format_config(const DaemonConfig& c);

}  // namespace roadload::firmware
