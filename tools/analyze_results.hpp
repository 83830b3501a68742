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
std::optional<ParseError> write_cells_csv(const std::string& path, const std::vector<CellResult>& cells,
                                          const std::vector<std::string>& axle_names);
std::optional<ParseError> write_trip_json(const std::string& path, const TripResult& trip);

// A simulation's truth folder: the true CRR per cell (cells.csv) and where the fuel went (truth.toml [fuel_breakdown]).
struct Truth {
  std::map<std::string, double> crr;
  std::map<std::string, double> energy_j;  // <row>_j; empty when truth.toml has no [fuel_breakdown]
};
Parsed<Truth> read_truth(const std::string& dir);

void print_cells(const std::vector<CellResult>& cells, const Truth* truth);
void print_trip(const TripResult& trip, const std::vector<CellResult>& cells, const Truth* truth);

}  // namespace roadload::cli
