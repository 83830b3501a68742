#pragma once
// The results files of a drive, written by `roadload analyze` from the smoother and by roadloadd
// from its live filter, so both read alike: RESULTS/cells.csv and RESULTS/trip.json.
#include <optional>
#include <string>
#include <vector>

#include "roadload/drive_analyzer.hpp"
#include "roadload/parse_error.hpp"
#include "roadload/results/provenance.hpp"
#include "roadload/route_geometry.hpp"
#include "roadload/vibration.hpp"

namespace roadload::results {

// Where a cell lies, for a map and for matching it to another drive's: its pavement's surface as
// the route file states it (empty where unknown) and its ends' coordinates.
struct CellPlace {
  std::string surface;
  GeoPoint start, end;
};
// Each span's place on `route`; `surfaces` per span, or empty.
std::vector<CellPlace> cell_places(const RouteGeometry& route, const std::vector<CellSpan>& spans,
                                   const std::vector<std::string>& surfaces);

// One row per cell, with its place (`places` per cell, or empty: the columns left blank); per axle (named as the contact-force layout
// names them) the mean and standard deviation of the contact force and the standard deviation of its dynamic part. With `vibration`,
// each cell also gets its dynamic rolling resistance: damper_power_w and tire_power_w (named as the simulator's truth),
// tire_eq27_power_w, and dynamic_energy_j, dynamic_l, dynamic_l_per_100km of the dampers and tires together.
// Each row ends with the drive's run, truck and road (recording_id, vin, vehicle_hash, route_hash,
// drive_start_utc, from `provenance` when given), so rows of many drives concatenated still say
// whose they are, then the reason.
std::optional<ParseError> write_cells_csv(const std::string& path, const std::vector<CellResult>& cells,
                                          const std::vector<std::string>& axle_names, const VibrationAnalysis* vibration,
                                          const std::vector<CellPlace>& places, const Provenance* provenance = nullptr);
// One row per pavement type: pavement,cells,length_m,samples,crr,crr_lo,crr_hi,crr_sigma,
// identified,speed_mps,rolling_l,distance_m,rolling_l_per_100km,reason.
std::optional<ParseError> write_pavements_csv(const std::string& path, const std::vector<PavementResult>& pavements);
// The same as trip.json's "pavements" member (`"pavements": [...]`).
std::string pavements_json(const std::vector<PavementResult>& pavements);
// `extra`: further members of the top-level object, already formatted (may be empty).
std::optional<ParseError> write_trip_json(const std::string& path, const TripResult& trip, const std::string& extra);

}  // namespace roadload::results
