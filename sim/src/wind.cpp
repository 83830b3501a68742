#include "roadload/sim/wind.hpp"

#include <cmath>
#include <initializer_list>
#include <numbers>

namespace roadload::sim {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr double kWanderTau_s = 300.0;
// Gusts evolve in time at a fixed point (not swept past the truck): 4 s is ~110 m at 64 mph.
constexpr double kGustTau_s = 4.0;

}  // namespace

WindField::WindField(const WeatherSpec& spec, double gust_sigma_mps, Rng rng) : spec_(spec), gust_sigma_(gust_sigma_mps), rng_(rng) {}

WindField::Decay WindField::decay(double sigma, double tau_s, double dt_s) {
  const double a = std::exp(-dt_s / tau_s);
  return {a, sigma * std::sqrt(1.0 - a * a)};
}

void WindField::advance(double dt_s) {
  t_s_ += dt_s;
  const auto& trace = spec_.wind_trace;
  while (trace_at_ + 1 < trace.size() && trace[trace_at_ + 1].t_s <= t_s_) ++trace_at_;
  if (dt_s != dt_s_) {  // the step is fixed in a run: exp() once, not six times a step
    dt_s_ = dt_s;
    wander_ = decay(spec_.wander_mps, kWanderTau_s, dt_s);
    gust_ = decay(gust_sigma_, kGustTau_s, dt_s);
  }
  if (spec_.wander_mps > 0) {
    wander_east_ = wander_.a * wander_east_ + wander_.b * rng_.normal();
    wander_north_ = wander_.a * wander_north_ + wander_.b * rng_.normal();
  }
  if (gust_sigma_ > 0) {
    for (double* g : {&gust_truck_east_, &gust_truck_north_, &gust_mast_east_, &gust_mast_north_}) {
      *g = gust_.a * *g + gust_.b * rng_.normal();
    }
  }
}

std::pair<double, double> WindField::mean_wind() const {
  const auto& trace = spec_.wind_trace;
  if (trace.empty()) {
    // Wind "from" 270 blows toward the east: its velocity points opposite to where it comes from.
    const double from = spec_.wind_from_deg * kDeg;
    return {-spec_.wind_speed_mps * std::sin(from) + wander_east_, -spec_.wind_speed_mps * std::cos(from) + wander_north_};
  }
  const WindPoint& a = trace[trace_at_];
  if (trace_at_ + 1 >= trace.size() || t_s_ <= a.t_s) return {a.east_mps, a.north_mps};
  const WindPoint& b = trace[trace_at_ + 1];
  const double w = (t_s_ - a.t_s) / (b.t_s - a.t_s);
  return {a.east_mps + w * (b.east_mps - a.east_mps), a.north_mps + w * (b.north_mps - a.north_mps)};
}

Environment WindField::compose(double gust_east, double gust_north) const {
  const auto [mean_east, mean_north] = mean_wind();
  const double east = mean_east + gust_east;
  const double north = mean_north + gust_north;
  Environment e;
  e.air_temp_c = spec_.air_temp_c + spec_.temp_drift_c_per_h * t_s_ / 3600.0;
  e.pressure_pa = spec_.pressure_pa;
  e.wind_speed_mps = std::hypot(east, north);
  e.wind_from_deg = std::fmod(std::atan2(-east, -north) / kDeg + 360.0, 360.0);
  return e;
}

}  // namespace roadload::sim
