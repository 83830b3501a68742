#pragma once
// Ground truth of a simulated drive: what really happened, which the recording cannot say.
//   series.csv  10 Hz interval means of every force, CRR, powers and engine quantities
//   axles.csv   100 Hz vertical tire force and damper/tire power per axle
//   cells.csv   one row per cell: true CRR and trip-mean dissipated powers (docs/simulator.md)
//   truth.toml  scenario, seed, effects on and their magnitudes, truck parameters
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "roadload/parse_error.hpp"
#include "roadload/recording/writer.hpp"
#include "roadload/sim/plant.hpp"
#include "roadload/sim/route.hpp"

namespace roadload::sim {

struct CellTruth {
  std::string id;
  std::string surface;
  double start_m = 0, end_m = 0;
  double crr = 0;             // force-weighted mean true CRR of the tires in the cell
  double damper_power_w = 0;  // sum over axles of each axle's mean damper power in the cell
  double tire_power_w = 0;
  double friction_power_w = 0;
  double speed_mps = 0;
  double time_s = 0;        // centre of gravity in the cell
  double roll_force_n = 0;  // mean
  double fuel_l = 0;
  bool complete = false;  // the whole truck crossed the whole cell
};

// The energy ledger in the rows of a fuel breakdown (seed report Figures 2.2, 6.4), in J:
// engine = thermal + friction, driveline = gear losses + clutch slip, accessories with the fan,
// rolling = static + dynamic (profile) rolling resistance, acceleration = kinetic energy gained.
struct BreakdownTruth {
  const char* name;
  double energy_j;
};
std::array<BreakdownTruth, 8> breakdown_truth(const EnergyLedger& e);

class TruthRecorder {
 public:
  TruthRecorder(const Route& route, const TruckParams& truck);
  // Writes series.csv and axles.csv as it goes when a folder is given.
  std::optional<ParseError> open(const std::string& folder);
  void observe(const TruckState& s, const Environment& env, double dt_s);
  std::vector<CellTruth> cells() const;
  std::optional<ParseError> finish(const std::string& truth_toml);

 private:
  struct CellAcc {
    double fz_dt = 0, crr_fz_dt = 0;
    std::array<double, kMaxAxles> axle_time{}, damper_j{}, tire_j{}, friction_j{};
    double time_s = 0, distance_m = 0, roll_j = 0, fuel_kg = 0;
    double first_x = 1e300, last_x = -1e300;
  };
  void flush_series(const TruckState& s);

  const Route& route_;
  TruckParams truck_;
  std::string folder_;
  recording::OutputFile series_, axles_;
  recording::LineBuilder line_;
  std::vector<CellAcc> acc_;
  // Interval means for series.csv.
  static constexpr std::size_t kSeriesFields = 17;
  std::array<double, kSeriesFields> sum_{};
  double sum_dt_ = 0;
  double next_series_s_ = 0.1;
  double next_axle_s_ = 0.01;
};

}  // namespace roadload::sim
