#include "roadload/model/longitudinal.hpp"

namespace roadload::model {

double flywheel_torque_nm(double actual_pct, double friction_pct, double parasitic_pct, double ref_torque_nm) {
  return (actual_pct - friction_pct - parasitic_pct) / 100.0 * ref_torque_nm;
}

double tractive_force_n(const TruckModel& m, double flywheel_torque_nm, double gear_ratio) {
  const double ideal = flywheel_torque_nm * gear_ratio * m.final_drive / m.tire_radius_m;
  return ideal >= 0 ? ideal * m.driveline_efficiency : ideal / m.driveline_efficiency;
}

double wheel_force_per_flywheel_nm(const TruckModel& m, double gear_ratio) {
  return gear_ratio * m.final_drive / m.tire_radius_m * m.driveline_efficiency;
}

double effective_mass_kg(const TruckModel& m, double gear_ratio) {
  const double k = gear_ratio * m.final_drive / m.tire_radius_m;
  return m.mass_kg + m.wheel_inertia_mass_kg + (m.engine_inertia_kgm2 + m.driveline_inertia_kgm2) * k * k;
}

double air_density_kgpm3(double pressure_pa, double temp_c) { return pressure_pa / (287.05 * (temp_c + 273.15)); }

}  // namespace roadload::model
