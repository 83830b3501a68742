#include "targets.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <system_error>

#include "roadload/firmware/config.hpp"
#include "roadload/geo_files.hpp"
#include "roadload/j1939/dbc.hpp"
#include "roadload/j1939/transport.hpp"
#include "roadload/recording/candump.hpp"
#include "roadload/recording/metadata.hpp"
#include "roadload/recording/reader.hpp"
#include "roadload/results/json.hpp"
#include "roadload/route_file.hpp"
#include "roadload/vehicle_file.hpp"

namespace roadload::fuzz {
namespace {

std::string_view text(const std::uint8_t* data, std::size_t size) { return {reinterpret_cast<const char*>(data), size}; }

// A property, not just "no crash": a violated one aborts so the fuzzer keeps the input.
void require(bool ok, const char* what) {
  if (!ok) {
    std::fprintf(stderr, "fuzz property violated: %s\n", what);
    std::abort();
  }
}

// A scratch folder of this process: the loaders that take a path read the input from a file in it.
// Removed when the process ends.
const std::filesystem::path& scratch() {
  struct Dir {
    std::filesystem::path path = std::filesystem::temp_directory_path() / ("roadload-fuzz-" + std::to_string(::getpid()));
    Dir() { std::filesystem::create_directories(path); }
    ~Dir() {
      std::error_code ec;
      std::filesystem::remove_all(path, ec);
    }
  };
  static const Dir dir;
  return dir.path;
}

std::string as_file(const std::string& name, std::string_view bytes) {
  const std::string path = (scratch() / name).string();
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
  return path;
}

// Whatever a loader refuses, it says why and where.
template <typename T>
bool refused(const Parsed<T>& p) {
  if (p) return false;
  require(!p.error().message.empty(), "an error says what is wrong");
  require(!p.error().file.empty(), "an error names its file");
  return true;
}

}  // namespace

void candump_line(const std::uint8_t* data, std::size_t size) {
  recording::InterfaceTable ifaces;
  CanFrame f;
  recording::LineResult result;
  const std::string_view line = text(data, size);
  if (line.find('\n') != std::string_view::npos) return;
  if (recording::parse_candump_line(line, ifaces, f, result) || result != recording::LineResult::frame) return;
  // Whatever parses must format back to a line that parses to the same frame.
  char buf[recording::kMaxLineChars];
  const std::size_t n = recording::format_candump_line(f, ifaces.name(f.iface), buf);
  require(n < sizeof buf, "formatted line fits");
  CanFrame g;
  require(!recording::parse_candump_line(std::string_view(buf, n), ifaces, g, result), "formatted line parses");
  require(g.kind == f.kind && g.id == f.id && g.len == f.len, "round trip keeps the frame");
  require(to_ns(g.t) / 1000 == to_ns(f.t) / 1000, "round trip keeps the stamp to the microsecond");
}

void dbc(const std::uint8_t* data, std::size_t size) {
  j1939::Database db;
  if (j1939::load_dbc(db, text(data, size), "fuzz.dbc")) {
    require(db.size() == 0, "a failed load leaves the database unchanged");
    return;
  }
  const std::uint8_t payload[8] = {0x12, 0x34, 0x56, 0x78, 0x9A, 0xBC, 0xDE, 0xF0};
  for (const auto& m : db.messages()) {
    for (const auto& s : m.signals) j1939::decode(s, payload);
  }
}

void metadata(const std::uint8_t* data, std::size_t size) {
  auto m = recording::parse_metadata(text(data, size), "meta.toml");
  if (!m) return;
  require(recording::parse_metadata(recording::format_metadata(m.value()), "again").ok(), "formatted metadata parses");
}

// The input is split at the first NUL byte into accel.csv and can.log of a recording folder.
void recording(const std::uint8_t* data, std::size_t size) {
  const std::filesystem::path& dir = scratch();
  const std::string_view all = text(data, size);
  const std::size_t split = std::min(all.find('\0'), all.size());
  std::ofstream(dir / "accel.csv", std::ios::trunc) << all.substr(0, split);
  std::ofstream(dir / "can.log", std::ios::trunc) << (split < all.size() ? all.substr(split + 1) : "");
  auto rec = recording::RecordingReader::open(dir.string());
  if (!rec) return;
  std::size_t n = 0;
  while (rec.value().next() != nullptr) ++n;
  require(n <= size, "no more records than bytes");
}

// A results file (trip.json) read back by `roadload report`; the paths it asks for are walked.
void json(const std::uint8_t* data, std::size_t size) {
  const auto doc = results::parse_json(text(data, size), "fuzz");
  if (!doc) {
    require(!doc.error().message.empty(), "an error says what is wrong");
    return;
  }
  (void)doc.value().number_at("fuel.rolling_l");
  if (const results::JsonValue* groups = doc.value().find("groups"))
    require(groups->items().size() <= size, "items bounded by input");
}

// Each 12-byte chunk is a frame: 4 bytes id, 1 byte length, 7 bytes of payload prefix; stamps
// advance by the first byte so timeouts are exercised too.
void transport(const std::uint8_t* data, std::size_t size) {
  j1939::TpConfig cfg;
  cfg.max_sessions = 4;
  cfg.max_etp_bytes = 4096;
  j1939::TpReassembler tp(cfg);
  std::int64_t t_ns = 0;
  for (std::size_t i = 0; i + 12 <= size; i += 12) {
    CanFrame f;
    f.kind = CanFrameKind::extended;
    f.id = (std::uint32_t{data[i]} << 24 | std::uint32_t{data[i + 1]} << 16 | std::uint32_t{data[i + 2]} << 8 | data[i + 3]) &
           0x1FFFFFFFu;
    if ((data[i] & 1) != 0) f.id = (f.id & 0xFF00FFFFu) | ((data[i] & 2) != 0 ? 0xEC0000u : 0xEB0000u);
    f.len = static_cast<std::uint8_t>(data[i + 4] % 9);
    for (std::size_t b = 0; b < 8; ++b) f.data[b] = data[i + 5 + (b % 7)];
    t_ns += std::int64_t{data[i + 5]} * 10'000'000;
    f.t = capture_time_from_ns(t_ns);
    if (auto m = tp.push(f)) require(!m->data.empty() && m->data.size() <= 4096, "message size bounded");
  }
  require(tp.open_sessions() <= cfg.max_sessions + cfg.max_etp_sessions, "sessions bounded");
}

// A vehicle file as --vehicle reads it: a truck that loads has a mass and a drag area that are
// numbers a model can use.
void vehicle(const std::uint8_t* data, std::size_t size) {
  const auto v = load_vehicle_file(as_file("vehicle.toml", text(data, size)));
  if (refused(v)) return;
  require(std::isfinite(v.value().mass_kg()) && v.value().mass_kg() > 0, "a loaded truck has a positive mass");
  require(std::isfinite(v.value().cda_m2) && v.value().cda_m2 > 0, "a loaded truck has a positive drag area");
}

// A route file: cells that load lie in order, each of positive length, with a CRR a tire can have.
void route(const std::uint8_t* data, std::size_t size) {
  const auto r = load_route_file(as_file("route.toml", text(data, size)));
  if (refused(r)) return;
  double end = -1e300;
  for (const CellDef& c : r.value().cells) {
    require(c.start_m < c.end_m, "a cell has a positive length");
    require(c.start_m >= end - 1e-6, "cells do not overlap");
    end = c.end_m;
    require(!c.crr || (*c.crr > 0 && *c.crr <= 0.05), "a cell's CRR is one a tire can have");
  }
  require(r.value().default_crr > 0 && r.value().default_crr <= 0.05, "the default CRR is one a tire can have");
}

// A road's line from GIS: the first byte chooses GeoJSON (even) or GPX (odd); what loads is finite.
void geo_line(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return;
  const auto line = load_geo_line(as_file(data[0] % 2 == 0 ? "road.geojson" : "road.gpx", text(data + 1, size - 1)));
  if (refused(line)) return;
  for (const GeoPoint& p : line.value()) {
    require(std::isfinite(p.lat_deg) && std::abs(p.lat_deg) <= 90 && std::isfinite(p.lon_deg) && std::abs(p.lon_deg) <= 180,
            "a point lies on the Earth");
  }
}

// roadloadd's configuration: one that loads passes the daemon's own validation.
void daemon_config(const std::uint8_t* data, std::size_t size) {
  const auto c = firmware::load_config(as_file("roadloadd.toml", text(data, size)));
  if (refused(c)) return;
  require(!firmware::validate(c.value()), "a loaded configuration is valid");
}

}  // namespace roadload::fuzz
