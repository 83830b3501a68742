#include "roadload/spectra/dynamic_power.hpp"

#include <cmath>
#include <numbers>

namespace roadload::spectra {
namespace {

// Sum of weight(f_k) * density_k * bin_hz over the band; bin 0 (f = 0) never counts.
template <typename Weight>
double integrate(std::span<const double> density, double bin_hz, PowerBand band, Weight weight) {
  double sum = 0;
  for (std::size_t k = 1; k < density.size(); ++k) {
    const double f = static_cast<double>(k) * bin_hz;
    if (f < band.lo_hz || f > band.hi_hz) continue;
    sum += weight(2.0 * std::numbers::pi * f) * density[k];
  }
  return sum * bin_hz;
}

}  // namespace

double dashpot_power_w(double damping_nspm, std::span<const double> accel_density, double bin_hz, PowerBand band) {
  return damping_nspm * integrate(accel_density, bin_hz, band, [](double w) { return 1.0 / (w * w); });
}

double dashpot_velocity_power_w(double damping_nspm, std::span<const double> velocity_density, double bin_hz, PowerBand band) {
  return damping_nspm * integrate(velocity_density, bin_hz, band, [](double) { return 1.0; });
}

double tire_deflection_power_w(double c_tire_nspm, double k_tire_npm, std::span<const double> force_density, double bin_hz,
                               PowerBand band) {
  return c_tire_nspm * integrate(force_density, bin_hz, band,
                                 [&](double w) { return w * w / (k_tire_npm * k_tire_npm + w * w * c_tire_nspm * c_tire_nspm); });
}

AnnualCost annual_cost(double power_w, const Duty& duty, double diesel_energy_jpl) {
  AnnualCost c;
  c.hours_per_year = duty.hours_per_year;
  const double energy_j = power_w * duty.hours_per_year * 3600.0;
  c.energy_mj_per_year = energy_j * 1e-6;
  c.diesel_l_per_year = energy_j / diesel_energy_jpl;
  c.l_per_100km = duty.km_per_year > 0 ? c.diesel_l_per_year / duty.km_per_year * 100.0 : 0.0;
  return c;
}

StretchCost stretch_cost(double power_w, double time_s, double speed_mps, double diesel_energy_jpl) {
  StretchCost c;
  c.energy_j = power_w * time_s;
  c.diesel_l = c.energy_j / diesel_energy_jpl;
  // Litres per 100 km = power / (speed x energy per litre) x 100 km.
  c.l_per_100km = speed_mps > 0 ? power_w / (speed_mps * diesel_energy_jpl) * 1e5 : 0.0;
  return c;
}

}  // namespace roadload::spectra
