#pragma once
// When a CRR may be reported as identified: its interval is tight enough, it lies where truck tires
// on any pavement lie, and every check that the model fits this drive holds. A number marked
// identified that is wrong is the worst output this product can give, so each check names itself
// when it fails and every failure is reported, not only the first.
#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "roadload/drive_results.hpp"

namespace roadload {

struct IdentificationLimits {
  // The filter's mean NIS within this many of its standard errors of 1: a model that fits the drive
  // gives innovations of the size it expects. The standard error comes from 5 s batches of a
  // correlated sequence and is itself uncertain by about a tenth; at 4 an honest drive fails about
  // once in 10,000, while a truck, road or sensor the model does not describe moves it further.
  double nis_z = 4.0;
  // Speed updates the NIS gate rejected, as a share of all: at the gate (chi-square(1) at 0.9999) a
  // consistent filter rejects 1e-4 of them, so more than 1 % means the speed it predicts is not the
  // speed the truck drove.
  double max_outlier_share = 0.01;
  // The force balance's closure over the drive: the work it leaves unexplained (what the
  // resistances, the speed's change and the brakes took, less the work at the wheels) as a share of
  // the work at the wheels. Under 0.2 % on every simulated drive, where the model is right; beyond
  // 5 % the balance does not close: another mass, drag area or grade, or a torque the model does
  // not see. Live, without the smoother's breakdown, it is not checked.
  double max_unexplained_work = 0.05;
  // The GNSS fixes must place the truck on the route: some fixes, and nearly all of those taken on
  // the road on it. Off the route's polyline by more than its tolerance (AnalyzerConfig), a share
  // above 5 % means another road or a route whose geometry is off.
  std::size_t min_fixes_on_route = 10;
  double max_off_route_share = 0.05;
  // Truck tires on any pavement: the seed report's cells span 0.0044-0.0072, tire makers' labels
  // 0.003-0.012. A CRR outside 0.002-0.02 is the model's error, not the road's.
  double min_crr = 0.002, max_crr = 0.02;
};

// How the filter's consistency failure begins, and how its reason names the side of the band it
// fell on: a results database reads a stored reason back by these (a cautious filter's estimate,
// below the band, is still evidence; one above it is not).
inline constexpr std::string_view kNisInconsistent = "the filter is not consistent with this drive: mean NIS ";
inline constexpr std::string_view kNisBelowBand = " (below it";
inline constexpr std::string_view kNisAboveBand = " (above it";

// The drive's own checks, each failure as a sentence naming the figure and its bound: the filter's
// consistency, its outliers, the fuel's closure and the GNSS track against the route. Empty when
// every one holds.
std::vector<std::string> drive_failures(const TripResult& trip, const IdentificationLimits& limits);

// A CRR estimate's own: its sigma against `max_sigma` and the physical range.
std::vector<std::string> estimate_failures(double crr, double sigma, double max_sigma, const IdentificationLimits& limits);

// A cell's verdict from its own checks and the drive's (`drive`, drive_failures()): sets
// `identified` and, when not, `reason`.
void judge_cell(CellResult& cell, double max_sigma, const IdentificationLimits& limits, const std::vector<std::string>& drive);

// The trip's failures: a force balance with usable ticks, its estimate's checks and the drive's.
std::vector<std::string> trip_failures(const TripResult& trip, bool usable, double max_sigma, const IdentificationLimits& limits);

// A reason from outside the drive's own checks (the truck assumed, the drive not placed): the trip
// and every cell are withheld from "identified" with it.
void withhold(TripResult& trip, std::vector<CellResult>& cells, const std::string& why);
void withhold(CellResult& cell, const std::string& why);

// "a; b; c".
std::string join_reasons(const std::vector<std::string>& reasons);

}  // namespace roadload
