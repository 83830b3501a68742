#pragma once
// The estimator's force balance along the road (seed report Eq. 2.2-2.4, TRMA):
//   m_eff dv/dt = F_tractive - 1/2 rho CdA v_air|v_air| - m g sin(grade) - CRR m g cos(grade)
// Written from the report and first principles, independently of the simulator's plant.
#include "roadload/model/engine_losses.hpp"
#include "roadload/time.hpp"

namespace roadload::model {

inline constexpr double kGravity_mps2 = 9.80665;

// What the estimator assumes about the truck; defaults are the MnROAD truck (report Tables 6.1-6.2).
struct TruckModel {
  double mass_kg = 36152.0;
  double wheel_inertia_mass_kg = 936.0;   // 18 wheel ends x 13 kg m^2 / r^2
  double tire_radius_m = 0.500;           // drive axles, dynamic
  double final_drive = 3.36;
  double driveline_efficiency = 0.94;
  double engine_inertia_kgm2 = 3.824;     // EC1 SPN 1794 when the truck sends it
  double driveline_inertia_kgm2 = 0.5;
  double cda_prior_m2 = 6.2;
  double cda_sigma_m2 = 0.6;
  // Between CdA's error and the flywheel torque bias's: a CdA calibrated from two speeds took up
  // the engine-loss calibration's error, which the same truck carries into every later drive.
  double cda_torque_bias_correlation = 0.0;
  double crr_prior = 0.0055;
  double crr_sigma = 0.002;
  // Friction + accessories by engine speed from a standstill calibration; empty: EEC3's.
  EngineLossMap engine_losses;
};

// Torque at the flywheel from EEC1/EEC3 percentages (J1939: actual torque is indicated; friction
// and the parasitic loads the ECU knows are subtracted).
double flywheel_torque_nm(double actual_pct, double friction_pct, double parasitic_pct, double ref_torque_nm);

// Tractive force at the wheels through gear and final drive; losses oppose the power flow.
double tractive_force_n(const TruckModel& m, double flywheel_torque_nm, double gear_ratio);

// How much wheel force one more N m at the flywheel makes in this gear (driving direction).
double wheel_force_per_flywheel_nm(const TruckModel& m, double gear_ratio);

// Mass the longitudinal motion sees: truck, wheels, and the engine side through the gear.
double effective_mass_kg(const TruckModel& m, double gear_ratio);

double air_density_kgpm3(double pressure_pa, double temp_c);

// Inputs of the force balance at one instant, all in SI.
struct ForceInputs {
  CaptureTime t;
  double tractive_n = 0;
  double air_density_kgpm3 = 1.2;
  double headwind_mps = 0;       // wind component blowing against the direction of travel
  double grade_rad = 0;
  double grade_sigma_rad = 0;    // the grade profile's uncertainty here
  double effective_mass_kg = 0;
  double wheel_force_per_flywheel_nm = 0;  // d(tractive force)/d(flywheel torque) in this gear, N per N m
  double crr_jump_variance = 0;  // CRR change allowed over this interval: axles crossing into a new cell
  double ripple_sigma_mps = 0;   // the road's roughness in the speed here (road_roughness.hpp)
  double ripple_correlation_m = 1.0;  // and the distance it stays correlated over
  bool usable = false;           // false while braking, shifting or declutched
};

}  // namespace roadload::model
