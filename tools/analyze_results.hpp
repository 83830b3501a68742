#pragma once
// What `roadload analyze` writes and prints: RESULTS/cells.csv and RESULTS/trip.json, and, given a
// simulation's ground truth, the estimate beside it.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "roadload/drive_analyzer.hpp"
#include "roadload/parse_error.hpp"

namespace roadload::cli {

// One row per cell; per axle (named as the contact-force layout names them) the mean and standard
// deviation of the contact force and the standard deviation of its dynamic part.
// With `vibration`, each cell also gets its dynamic rolling resistance: damper_power_w and
// tire_power_w (named as the simulator's truth), tire_eq27_power_w, and dynamic_energy_j,
// dynamic_l, dynamic_l_per_100km of the dampers and tires together.
std::optional<ParseError> write_cells_csv(const std::string& path, const std::vector<CellResult>& cells,
                                          const std::vector<std::string>& axle_names, const VibrationAnalysis* vibration);
// `extra`: further members of the top-level object, already formatted (may be empty).
std::optional<ParseError> write_trip_json(const std::string& path, const TripResult& trip, const std::string& extra);

// A simulation's truth folder: the true CRR per cell (cells.csv) and where the fuel went (truth.toml [fuel_breakdown]).
struct Truth {
  std::map<std::string, double> crr;
  std::map<std::string, double> damper_w, tire_w;  // each axle's mean in the cell, summed over axles
  std::map<std::string, double> time_s;            // the centre of gravity's time in the cell
  std::map<std::string, double> energy_j;  // <row>_j; empty when truth.toml has no [fuel_breakdown]
};
Parsed<Truth> read_truth(const std::string& dir);

void print_cells(const std::vector<CellResult>& cells, const Truth* truth);
void print_trip(const TripResult& trip, const std::vector<CellResult>& cells, const Truth* truth);

}  // namespace roadload::cli
