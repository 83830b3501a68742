#include "roadload/model/longitudinal.hpp"

#include <cmath>

namespace roadload::model {

TruckModel truck_model(const Vehicle& v) {
  TruckModel m;
  m.mass_kg = v.mass_kg();
  const VehicleAxle* drive = v.drive_axle();
  m.tire_radius_m = drive != nullptr ? drive->tire_radius_m : 0.0;
  double wheel_inertia = 0;
  for (const VehicleAxle& a : v.axles) wheel_inertia += a.wheel_inertia_kgm2;
  if (m.tire_radius_m > 0) m.wheel_inertia_mass_kg = wheel_inertia / (m.tire_radius_m * m.tire_radius_m);
  m.final_drive = v.driveline.final_drive;
  m.driveline_efficiency = v.driveline.efficiency;
  m.engine_inertia_kgm2 = v.engine.inertia_kgm2;
  m.driveline_inertia_kgm2 = v.driveline.inertia_kgm2;
  m.cda_prior_m2 = v.cda_m2;
  m.cda_sigma_m2 = v.cda_sigma_m2;
  m.torque_scale_sigma = v.engine.torque_scale_sigma;
  m.efficiency_scale_sigma = v.driveline.efficiency > 0 ? v.driveline.efficiency_sigma / v.driveline.efficiency : 0.0;
  m.mass_sigma_kg = v.mass_sigma_kg;
  return m;
}

Resistances resistances(double mass_kg, double crr, double cda_m2, double air_density_kgpm3, double airspeed_mps, double grade_rad,
                        double grade_error_rad) {
  const double weight = mass_kg * kGravity_mps2;
  const double half_rho = 0.5 * air_density_kgpm3;
  Resistances r;
  r.aero_n = half_rho * cda_m2 * airspeed_mps * std::abs(airspeed_mps);
  r.rolling_n = crr * weight * std::cos(grade_rad);
  r.grade_n = weight * (std::sin(grade_rad) + std::cos(grade_rad) * grade_error_rad);
  return r;
}

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
