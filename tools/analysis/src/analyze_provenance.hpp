#pragma once
// Where a drive's results came from, in trip.json beside them: the program, the recording, the
// truck, the route, when it was driven and the calibration the force balance used. A number
// without these cannot be compared with another drive's, nor checked.
#include <string>
#include <vector>

#include "analyze_options.hpp"
#include "gnss_tracks.hpp"
#include "roadload/drive_analyzer.hpp"
#include "roadload/recording/metadata.hpp"
#include "roadload/vehicle.hpp"

namespace roadload::cli {

struct Provenance {
  std::vector<std::string> recordings;  // the folders or logs read, in order
  std::string recording_id;             // a logger run's, when its meta.toml gives one
  std::string vehicle, vin;             // the truck's name and VIN as described
  std::string vehicle_source;           // "--vehicle FILE", "the recording's meta.toml", or why it is assumed
  std::string vehicle_hash;             // of the vehicle description as analysed: equal hashes, the same truck model
  std::string route;                    // a route file or name, or how the road was traced
  std::string route_name, route_hash;   // the route's own name; a hash of its geometry and sections
  std::string drive_start_utc;          // ISO 8601 of the first fix that tells UTC; empty when none did
  std::string drive_end_utc;            // of the last
  std::string engine_losses;            // the engine-loss table, or EEC3's nominal friction
  std::string cda;                      // the drag area prior's source
  std::string torque_scale;             // the engine torque's scale and its sigma, when given
};

// A road as results name it: equal hashes, the same geometry cut into the same sections.
struct RouteIdentity {
  std::string name, hash;
};

// What trip.json says the results of `o` came from: the truck as described (or why assumed), the
// road the drive was placed on and the configuration the force balance ran with.
Provenance provenance(const AnalyzeOptions& o, const recording::Metadata& meta, const Vehicle& vehicle, const std::string& assumed,
                      const RecordedTrack& track, const AnalyzerConfig& cfg, const RouteIdentity& road);

// trip.json's "provenance" member (`"provenance": {...}`).
std::string provenance_json(const Provenance& p);

}  // namespace roadload::cli
