#pragma once
// Dynamic rolling resistance from accelerometer spectra: seed report Eq. 2.5-2.8 and Table 6.6.
//
// A dashpot of coefficient d [N s/m] moved at velocity v dissipates P = d <v^2>. Given the one-sided
// density S_a(f) of the acceleration across it in (m/s^2)^2/Hz, the velocity's density is
// S_a(f) / (2 pi f)^2 in (m/s)^2/Hz, so
//
//     P [W] = d * integral over f [Hz] of S_a(f) / (2 pi f)^2 df.
//
// The density is per Hz and the integral is over Hz; a per-rad/s density would be integrated over
// rad/s. Mixing the two is the 2 pi error the report's units invite. The sum runs over the Welch
// bins (rectangle rule, the bins' own width) from `lo_hz`: below it the 1/f^2 weight turns a MEMS
// part's offset wander and the window's leakage of the static 1 g into watts. 0.5 Hz (default)
// is a third of the 1.5 Hz body modes, where a suspension's relative motion has already faded to a
// few percent of its amplitude at the mode (docs/spectra.md, "Low-frequency cutoff").
#include <span>

namespace roadload::spectra {

struct PowerBand {
  double lo_hz = 0.5;
  double hi_hz = 1e9;  // default: to Nyquist
};

// d * sum_k S_k / (2 pi f_k)^2 * bin_hz over lo_hz <= f_k <= hi_hz; bin k is at k * bin_hz.
double dashpot_power_w(double damping_nspm, std::span<const double> accel_density, double bin_hz, PowerBand band = {});
// The same from the velocity's density (m/s)^2/Hz: d x sum_k S_k x bin_hz over the band.
double dashpot_velocity_power_w(double damping_nspm, std::span<const double> velocity_density, double bin_hz, PowerBand band = {});

// A tire's dissipation on its deflection rate rather than on the axle's absolute velocity (Eq. 2.7).
// The dynamic tire force F = M_w a_w + M_c a_c (Eq. 2.1) drives the tire's spring and dashpot in
// parallel: F = k_t x + c_t x', so x' = i w F / (k_t + i w c_t) and
//     P = c_t * integral of S_F(f) w^2 / (k_t^2 + w^2 c_t^2) df,   w = 2 pi f,
// with S_F the dynamic force's density in N^2/Hz. Road input is in F already; what is left out is
// the tire's own mass and its enveloping of short bumps.
double tire_deflection_power_w(double c_tire_nspm, double k_tire_npm, std::span<const double> force_density, double bin_hz,
                               PowerBand band = {});

// What a power costs over a year of driving, Table 6.6: hours per year, energy, diesel and litres
// per 100 km. The report's figures imply 36.4 MJ per litre (its 51,530 MJ are 1,416 L).
struct Duty {
  double hours_per_year = 2207;  // 120,000 miles a year at 54.4 mph (report, Sect. 6.3)
  double km_per_year = 120000 * 1.609344;
};
struct AnnualCost {
  double hours_per_year = 0;
  double energy_mj_per_year = 0;
  double diesel_l_per_year = 0;
  double l_per_100km = 0;
};
AnnualCost annual_cost(double power_w, const Duty& duty, double diesel_energy_jpl);

// The same for a stretch of road: energy over `time_s`, litres, and litres per 100 km at `speed_mps`.
struct StretchCost {
  double energy_j = 0;
  double diesel_l = 0;
  double l_per_100km = 0;
};
StretchCost stretch_cost(double power_w, double time_s, double speed_mps, double diesel_energy_jpl);

}  // namespace roadload::spectra
