#include "roadload/sim/air.hpp"

#include <cmath>
#include <numbers>

#include "roadload/sim/units.hpp"

namespace roadload::sim {

double air_density_kgpm3(double pressure_pa, double temp_c) {
  return pressure_pa / (kAirGasConstant_jpkgk * (temp_c + kZeroCelsius_k));
}

RelativeWind relative_wind(double speed_mps, double heading_deg, double wind_speed_mps, double wind_from_deg) {
  constexpr double kDeg = std::numbers::pi / 180.0;
  // Angle between where the truck goes and where the wind comes from: 0 is a pure head wind.
  const double beta = (wind_from_deg - heading_deg) * kDeg;
  const double head = wind_speed_mps * std::cos(beta);
  const double cross = wind_speed_mps * std::sin(beta);
  const double along = speed_mps + head;
  return {along, std::atan2(cross, along)};
}

}  // namespace roadload::sim
