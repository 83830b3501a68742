#pragma once
// Each figure of the report as a chart built from the results (and, where given, the truth).
#include <optional>
#include <string>
#include <vector>

#include "roadload/report/svg_chart.hpp"
#include "roadload/results/results_dir.hpp"
#include "roadload/results/truth_files.hpp"

namespace roadload::report {

struct Figure {
  Chart chart;
  std::string caption;
};

// The seed report's figure each one stands for is in its caption.
Figure crr_per_cell(const results::NumberTable& cells, const results::Truth* truth);
Figure rolling_fuel_per_cell(const results::NumberTable& cells);
Figure fuel_breakdown_per_cell(const results::NumberTable& cells);
Figure trip_fuel_breakdown(const results::JsonValue& trip, const results::Truth* truth);
std::optional<Figure> contact_forces(const results::NumberTable& cells);
std::optional<Figure> dynamic_power_per_cell(const results::NumberTable& cells, const results::Truth* truth);
// The group's modes and joint line, from trip.json's dynamic_rolling.groups, as markers.
Figure spectrum(const results::Spectrum& s, const results::JsonValue& trip);

// Axle names as cells.csv spells its fz_<axle>_mean_n columns.
std::vector<std::string> axle_names(const results::NumberTable& cells);
std::vector<std::string> cell_ids(const results::NumberTable& cells);
// trip.json's dynamic_rolling.groups (one per pavement group); nullptr without accelerometers.
const results::JsonValue* pavement_groups(const results::JsonValue& trip);

}  // namespace roadload::report
