#pragma once
// A simulation's ground truth folder (`roadload simulate --truth`), read back for comparisons: the
// true CRR and dissipation per cell (cells.csv) and where the fuel went (truth.toml [fuel_breakdown]).
#include <map>
#include <string>

#include "roadload/parse_error.hpp"

namespace roadload::results {

struct Truth {
  std::map<std::string, double> crr;
  std::map<std::string, double> damper_w, tire_w;  // each axle's mean in the cell, summed over axles
  std::map<std::string, double> time_s;            // the centre of gravity's time in the cell
  std::map<std::string, double> energy_j;          // <row>_j; empty when truth.toml has no [fuel_breakdown]
};

Parsed<Truth> read_truth(const std::string& dir);

}  // namespace roadload::results
