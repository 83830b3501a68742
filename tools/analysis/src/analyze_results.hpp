#pragma once
// What `roadload analyze` writes and prints: RESULTS/cells.csv and RESULTS/trip.json, and, given a
// simulation's ground truth, the estimate beside it.
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "roadload/drive_analyzer.hpp"
#include "roadload/parse_error.hpp"
#include "roadload/results/results_files.hpp"
#include "roadload/results/truth_files.hpp"
#include "roadload/vibration.hpp"

namespace roadload::cli {

using results::read_truth;
using results::Truth;

void print_cells(const std::vector<CellResult>& cells, const Truth* truth);
// The answer per pavement type: CRR with its interval, identified or not, and the rolling
// resistance's fuel per 100 km on it.
void print_pavements(const std::vector<PavementResult>& pavements);
// With the accelerometers' analysis, the tires' own CRR too (tire_crr.hpp).
void print_trip(const TripResult& trip, const std::vector<CellResult>& cells, const Truth* truth, const VibrationAnalysis* vibration);

}  // namespace roadload::cli
