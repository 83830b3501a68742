#pragma once
// What `roadload analyze` reports of the accelerometers' spectra: dynamic rolling resistance per
// cell, per pavement group and per trip, the PSD files, the modes and the joint line per group.
#include <optional>
#include <string>
#include <vector>

#include "analyze_results.hpp"
#include "roadload/parse_error.hpp"
#include "roadload/pavement_groups.hpp"
#include "roadload/route_file.hpp"
#include "roadload/spectra/dynamic_power.hpp"
#include "roadload/spectra/modes.hpp"
#include "roadload/vibration.hpp"

namespace roadload::cli {

struct GroupSpectra {
  std::string name;
  DynamicPower power;
  double speed_mps = 0;
  double expected_panel_m = 0;
  spectra::JointLine joint;                       // guided by the inventory where it has a panel length, else blind
  double joint_hz = 0;                            // speed / panel length
  std::vector<std::vector<spectra::Peak>> peaks;  // per sensor, from the group's PSD
};

struct VibrationSummary {
  DynamicPower trip;
  spectra::StretchCost trip_cost;
  spectra::AnnualCost annual;
  std::vector<GroupSpectra> groups;
};

VibrationSummary summarize(const VibrationAnalysis& va, const PavementGroups& groups, double trip_time_s, double trip_distance_m);

// DIR/psd.csv (trip), DIR/psd-<group>.csv per group: freq_hz and one column per sensor, in
// (m/s^2)^2/Hz; DIR/psd-spatial-<group>.csv: cycles_per_m and one column per sensor, per cycle/m.
std::optional<ParseError> write_psd_files(const std::string& dir, const VibrationAnalysis& va, const PavementGroups& groups);

// The "dynamic_rolling" member of trip.json (no trailing comma or newline).
std::string vibration_json(const VibrationSummary& s);

void print_vibration(const VibrationSummary& s);
// Dampers and tires per cell against a simulation's truth: worst cell and the mean over cells.
void print_vibration_truth(const VibrationAnalysis& va, const std::vector<CellDef>& cells, const Truth& truth);

}  // namespace roadload::cli
