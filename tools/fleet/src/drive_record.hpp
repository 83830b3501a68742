#pragma once
// What a results folder says of one drive, in the database's terms.
#include <optional>
#include <string>
#include <vector>

#include "roadload/db/database.hpp"

namespace roadload::fleet {

struct SectionRecord {
  std::string key;  // route hash + ":" + cell
  std::string cell, surface, direction;
  double start_m = 0, end_m = 0;
  double start_lat = 0, start_lon = 0, end_lat = 0, end_lon = 0;
  bool placed = false;  // both ends have coordinates
};

struct DriveRecord {
  std::string dir;
  std::string drive_key, recording_id, results_hash;
  std::string vehicle_key, vin, vehicle_name, vehicle_hash, vehicle_source;
  std::string route_hash, route_name, route;
  std::string start_utc, end_utc, program, engine_losses, cda_prior, torque_scale;
  db::Value crr, crr_sigma, crr_identified, mass_kg, cda_m2, distance_m, fuel_l;
  std::vector<SectionRecord> sections;
  std::vector<db::Row> results;  // per section: the section_results columns after the two keys
};

// The section_results columns a DriveRecord's rows hold, in order.
extern const char* const kResultColumns[];
extern const std::size_t kResultColumnCount;

// Reads `dir` (cells.csv, trip.json). Throws ResultsError naming the file and field.
DriveRecord read_drive(const std::string& dir);

// The four-point compass direction of travel from a section's ends: NB, EB, SB or WB.
std::string direction_of(double start_lat, double start_lon, double end_lat, double end_lon);

}  // namespace roadload::fleet
