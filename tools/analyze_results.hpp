#pragma once
// What `roadload analyze` writes and prints: RESULTS/cells.csv and RESULTS/trip.json, and, given a
// simulation's ground truth, the estimate beside it.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "roadload/drive_analyzer.hpp"
#include "roadload/parse_error.hpp"
#include "roadload/vibration.hpp"
#include "roadload/results/results_files.hpp"

namespace roadload::cli {

// A simulation's truth folder: the true CRR per cell (cells.csv) and where the fuel went (truth.toml [fuel_breakdown]).
struct Truth {
  std::map<std::string, double> crr;
  std::map<std::string, double> damper_w, tire_w;  // each axle's mean in the cell, summed over axles
  std::map<std::string, double> time_s;            // the centre of gravity's time in the cell
  std::map<std::string, double> energy_j;  // <row>_j; empty when truth.toml has no [fuel_breakdown]
};
Parsed<Truth> read_truth(const std::string& dir);

void print_cells(const std::vector<CellResult>& cells, const Truth* truth);
// With the accelerometers' analysis, the tires' own CRR too (tire_crr.hpp).
void print_trip(const TripResult& trip, const std::vector<CellResult>& cells, const Truth* truth,
                const VibrationAnalysis* vibration);

}  // namespace roadload::cli
