#pragma once
// Where a drive's results came from, in trip.json beside them (roadload analyze's and roadloadd's
// alike): the program, the recording, the truck, the route, when it was driven and the
// calibration the force balance used. A number without these cannot be compared with another
// drive's, nor checked, nor merged into a fleet's database (docs/fleet.md).
#include <string>
#include <vector>

namespace roadload::results {

struct Provenance {
  std::string program;                  // "roadload 0.1.0", "roadloadd 0.1.0"
  std::vector<std::string> recordings;  // the folders or logs read, in order
  std::string recording_id;             // a logger run's, when its meta.toml gives one
  std::string vehicle, vin;             // the truck's name and VIN as described
  std::string vehicle_source;           // where the description came from, or why it is assumed
  std::string vehicle_hash;             // of the vehicle description as analysed: equal hashes, the same truck model
  std::string route;                    // a route file or name, or how the road was traced
  std::string route_name, route_hash;   // the route's own name; a hash of its geometry and sections
  std::string drive_start_utc;          // ISO 8601 of the first fix that tells UTC; empty when none did
  std::string drive_end_utc;            // of the last
  std::string engine_losses;            // the engine-loss table, or EEC3's nominal friction
  std::string cda;                      // the drag area prior and its source
  std::string torque_scale;             // the engine torque's scale and its sigma, when given
};

// "6.200 m2 +- 0.600 (the vehicle file)": the drag area prior and where it came from.
std::string cda_text(double cda_m2, double sigma_m2, const std::string& source);
// The engine-loss table's path, or what stands in for one when none is given.
std::string engine_losses_text(const std::string& table);

// trip.json's "provenance" member (`  "provenance": {...}`), empty fields as null.
std::string provenance_json(const Provenance& p);

}  // namespace roadload::results
