#pragma once
// Air around the truck and at the weather mast. The mean wind wanders slowly (both places see
// the same); gusts (the wind-gusts effect) are turbulence, independent at the truck and at a mast
// hundreds of metres away, so a roadside anemometer cannot measure the gusts the truck meets.
#include <utility>
#include <vector>

#include "roadload/sim/air.hpp"
#include "roadload/sim/random.hpp"

namespace roadload::sim {

// The mean wind's velocity (where it blows to) at a time of the run, as a roadside anemometer
// recorded it: a re-simulation replays it instead of drawing its own wander.
struct WindPoint {
  double t_s = 0;
  double east_mps = 0, north_mps = 0;
};

struct WeatherSpec {
  double air_temp_c = 15.0;
  double pressure_pa = 98100.0;
  double wind_speed_mps = 0.0;
  double wind_from_deg = 0.0;
  double wander_mps = 0.3;  // slow variation of the mean wind, standard deviation
  double temp_drift_c_per_h = 0.0;
  std::vector<WindPoint> wind_trace;  // in time order; when given it is the mean wind (no wander)
};

class WindField {
 public:
  WindField(const WeatherSpec& spec, double gust_sigma_mps, Rng rng);
  void advance(double dt_s);
  Environment at_truck() const { return compose(gust_truck_east_, gust_truck_north_); }
  Environment at_mast() const { return compose(gust_mast_east_, gust_mast_north_); }

 private:
  Environment compose(double gust_east, double gust_north) const;
  // The mean wind now, east and north components of its velocity.
  std::pair<double, double> mean_wind() const;
  // First-order Gauss-Markov step x' = a x + b w for a fixed step.
  struct Decay {
    double a = 1, b = 0;
  };
  static Decay decay(double sigma, double tau_s, double dt_s);

  WeatherSpec spec_;
  double gust_sigma_;
  Rng rng_;
  double t_s_ = 0;
  double dt_s_ = 0;
  std::size_t trace_at_ = 0;  // the trace point at or before t_s_
  Decay wander_, gust_;
  double wander_east_ = 0, wander_north_ = 0;
  double gust_truck_east_ = 0, gust_truck_north_ = 0, gust_mast_east_ = 0, gust_mast_north_ = 0;
};

}  // namespace roadload::sim
