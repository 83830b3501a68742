#pragma once
// What a drive's analysis gives: each cell's CRR with its interval, the trip's, and the filter's
// estimate now (roadloadd's status).
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "roadload/contact_forces.hpp"
#include "roadload/crr_filter.hpp"
#include "roadload/drive_signals.hpp"
#include "roadload/fuel_breakdown.hpp"
#include "roadload/time.hpp"

namespace roadload {

// The filter's estimate now, as the daemon's status shows it.
struct LiveEstimate {
  CaptureTime t{};
  bool started = false;
  double speed_mps = 0;
  double s_front_m = 0;  // along the route
  int cell = -1;         // index of the cell under the centre of gravity; -1 off the cells
  double crr = 0, crr_lo = 0, crr_hi = 0;
  bool identified = false;
  const char* not_identified = nullptr;  // the first live check that fails, while one does (static text)
  bool usable = false;                   // the last tick entered the force balance
};

struct CellResult {
  std::string id;
  double start_m = 0, end_m = 0;
  std::size_t samples = 0;  // usable filter ticks with every axle in the cell (the centre of gravity if it is shorter than the truck)
  double crr = 0, crr_sigma = 0, crr_lo = 0, crr_hi = 0;
  bool identified = false;
  std::string reason;  // why not, when not
  double speed_mps = 0;
  double roll_force_n = 0;              // CRR x weight
  double weight_n = 0;                  // the truck's weight that CRR is a coefficient of
  FuelBreakdown fuel;                   // over the time the centre of gravity was in the cell
  std::vector<AxleForceStats> contact;  // per axle of the attached ContactForces' layout (Eq. 2.1)
};

// A pavement type's answer: its CRR over every usable tick on its cells together (the smoother's
// variance of that mean, not an average of the cells' CRRs, whose errors the filter shares), and
// what rolling on it costs in fuel.
struct PavementResult {
  CellResult crr;         // id: the pavement's name; start_m 0, end_m the length of its cells
  std::size_t cells = 0;  // of the route's
  double rolling_l = 0;   // the rolling resistance's share of the fuel burnt on it
  double distance_m = 0;  // driven on it
  double rolling_l_per_100km() const { return distance_m > 0 ? rolling_l / distance_m * 1e5 : 0.0; }
};

struct TripResult {
  std::size_t ticks = 0, usable_ticks = 0;
  std::size_t coasting_ticks = 0;                      // of the usable, in neutral: the road's load without the engine
  std::array<std::size_t, kUnusableCount> unusable{};  // ticks by Unusable
  double crr = 0, crr_sigma = 0, cda_m2 = 0, torque_bias_nm = 0, torque_bias_sigma_nm = 0;
  // The mass the drive's grades and accelerations tell, with its standard error (the declared
  // mass and its prior's sigma where they tell nothing).
  double mass_kg = 0, mass_sigma_kg = 0;
  bool identified = false;
  std::size_t gnss_used = 0, gnss_off_route = 0;
  // Weather samples that measured the wind: without one the drag's airspeed is a guess.
  std::size_t wind_samples = 0;
  std::size_t no_fuel_rate = 0;  // ticks without LFE1: the breakdown's measured fuel misses them
  CrrCounters filter;
  // Mean NIS of the speed updates and its standard error from means of batches of consecutive
  // updates (the innovations are correlated over a few ticks, so a plain chi-square band is too
  // narrow): the noise model is consistent when the mean lies within 1 +- 1.96 se.
  double mean_nis = 0, mean_nis_se = 0;
  FuelBreakdown fuel;
  // Why the trip's CRR is not identified (identification.hpp), every failed check; empty when it is.
  std::vector<std::string> not_identified;
};

}  // namespace roadload
