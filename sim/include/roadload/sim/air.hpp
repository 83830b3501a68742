#pragma once
// The air the truck pushes through: density from the weather, wind as seen from the truck.
namespace roadload::sim {

// The air at the truck: the true values, before any sensor sees them.
// Wind is meteorological: the direction it blows from.
struct Environment {
  double air_temp_c = 15.0;
  double pressure_pa = 101325.0;
  double wind_speed_mps = 0.0;
  double wind_from_deg = 0.0;
};

// Dry-air ideal gas. Humidity (0.5-1 % lighter at 30 C) is left to the air-density effect.
double air_density_kgpm3(double pressure_pa, double temp_c);

struct RelativeWind {
  double airspeed_mps;  // along the truck's axis, positive from ahead
  double yaw_rad;       // angle of the relative wind to the truck's axis
};

// `wind_from_deg` is meteorological (where the wind comes from); `heading_deg` is the truck's course.
RelativeWind relative_wind(double speed_mps, double heading_deg, double wind_speed_mps, double wind_from_deg);

}  // namespace roadload::sim
