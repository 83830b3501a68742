#include "gnss_tracks.hpp"

#include "files.hpp"
#include "roadload/bus_position.hpp"
#include "roadload/j1939/assembler.hpp"
#include "roadload/recording/reader.hpp"

namespace roadload::cli {
namespace {

// The antenna height: --antenna-height, else the vehicle's (--vehicle or the recording's file),
// else meta.toml's bare value; without any, heights stay the antenna's and the user is told.
std::optional<int> antenna_height(std::string_view command, const std::string& path, const TrackOptions& o,
                                  const recording::Metadata& meta, RecordedTrack& t) {
  const auto it = meta.vehicle.find("gnss_antenna_height_m");
  if (o.antenna_height_m) {
    t.antenna_height_m = *o.antenna_height_m;
  } else if (!o.vehicle.empty() || meta.vehicle_file) {
    auto described = recording_vehicle(command, meta, o.vehicle);
    if (const int* rc = std::get_if<int>(&described)) return *rc;
    t.antenna_height_m = std::get<RecordingVehicle>(described).vehicle.gnss_antenna_height_m;
  } else if (it != meta.vehicle.end()) {
    t.antenna_height_m = it->second;
  } else {
    say(command, path + ": meta.toml: vehicle.gnss_antenna_height_m: not given; heights are the antenna's");
  }
  return std::nullopt;
}

}  // namespace

std::optional<int> read_recorded_track(std::string_view command, const std::vector<std::string>& segments, const TrackOptions& o,
                                       const j1939::Database& db, RecordedTrack& t, std::uint64_t& malformed) {
  // One read of both: the logger's own receiver where it has one, else the truck's, as its bus
  // broadcasts it.
  const std::string& path = segments.front();
  auto reader = recording::RecordingReader::open_drive(segments, recording::kGnssStream | recording::kCanStream);
  if (!reader) {
    say(command, reader.error().to_string());
    return exit_for(reader.error());
  }
  t.path = path;
  if (auto rc = antenna_height(command, path, o, reader.value().metadata(), t)) return rc;
  j1939::MessageAssembler assembler;
  BusPosition position(db);
  std::vector<GnssFix> bus;
  bool altitude = false;
  while (const recording::Record* r = reader.value().next()) {
    if (const auto* f = std::get_if<GnssFix>(r)) {
      t.fixes.push_back(*f);
    } else if (const auto* frame = std::get_if<CanFrame>(r)) {
      const auto m = assembler.push(*frame);
      if (!m) continue;
      if (auto placed = position.push(*m)) {
        altitude = altitude || placed->mode == GnssFixMode::fix_3d;
        bus.push_back(*placed);
      }
    }
  }
  malformed += reader.value().errors().count();
  if (o.print_errors) tell_errors(command, path, reader.value().errors());
  if (!t.fixes.empty()) {
    t.fixes.shrink_to_fit();  // kept through the analysis: not its growth's slack
    t.source = "gnss.csv";
  } else if (!bus.empty()) {
    t.fixes = std::move(bus);
    t.source = altitude ? "J1939 VP1 and VDS" : "J1939 VP1 (no altitude: VDS not sent)";
  }
  return std::nullopt;
}

}  // namespace roadload::cli
