#pragma once
// The seed report's own numbers as the real data: Tables 6.5 and 6.6 give the suspension power on
// concrete and bituminous pavements (Mainline at 30 mph, TH 10 and TH 66 at 55 mph). A simulation
// that knows only each pavement's IRI is compared with them; each candidate effect that acts on
// the vertical dynamics is fitted to the Mainline's concrete-to-bituminous ratio and judged on
// the highways' ratio, which it never saw.
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "roadload/j1939/database.hpp"
#include "roadload/parse_error.hpp"
#include "roadload/sim/effects.hpp"

namespace roadload::gap {

struct PavementPower {
  std::string name;
  double report_w = 0;
  double before_w = 0;  // IRI only
  double after_w = 0;   // with the chosen effect
};

struct TableCandidate {
  sim::Effect effect;
  std::vector<std::pair<double, double>> mainline_ratio;  // (magnitude, concrete / bituminous) simulated
  bool reached = false;                                   // some magnitude in range gives the report's Mainline ratio
  double magnitude = 0;                                   // that magnitude, or the one coming closest
  double highway_ratio = 0;                               // TH 10 / TH 66 at it: held out
  double holdout_error = 0;                               // |highway ratio - the report's| / the report's
};

// One nominal parameter of the truck (nominal.hpp) against the tables: how much it moves the
// Mainline's suspension power at one sigma and, when it moves it, the choice made again at both
// ends of its 90 % interval.
struct TablesNominal {
  std::string name, unit;
  double value = 0, sigma = 0;
  double power_per_sigma = 0;  // the larger relative change of the Mainline's two pavements
  struct End {
    double value = 0;
    std::optional<sim::Effect> effect;  // none reaches the Mainline ratio
    double magnitude = 0, highway_ratio = 0;
  };
  std::vector<End> ends;  // empty: the parameter does not move the power
};

struct TablesResult {
  std::vector<PavementPower> rows;  // Mainline bituminous, Mainline concrete, TH 66, TH 10
  std::vector<TableCandidate> candidates;
  int chosen = -1;  // index into candidates; -1: none reaches the Mainline ratio
  std::vector<TablesNominal> nominal;
};

inline constexpr double kReportMainlineRatio = 652.0 / 442.0;
inline constexpr double kReportHighwayRatio = 9353.0 / 6486.0;

// The choice on the vehicle file's truck, then each nominal parameter's check.
Parsed<TablesResult> compare_tables(const std::string& data_dir, const j1939::Database& db, unsigned jobs,
                                    const std::function<void(const std::string&)>& progress);

}  // namespace roadload::gap
