#pragma once
// The estimator's force balance along the road (seed report Eq. 2.2-2.4, TRMA):
//   m_eff dv/dt = F_tractive - 1/2 rho CdA v_air|v_air| - m g sin(grade) - CRR m g cos(grade)
// Written from the report and first principles, independently of the simulator's plant.
#include "roadload/model/engine_losses.hpp"
#include "roadload/time.hpp"
#include "roadload/vehicle.hpp"

namespace roadload::model {

inline constexpr double kGravity_mps2 = 9.80665;

// What the estimator assumes about the truck: truck_model() takes it from a vehicle description.
struct TruckModel {
  double mass_kg = 0;
  // Every wheel end's J / r^2 referred to the drive tires, whose speed CCVS1 reports; the steer
  // tires' larger radius is within a percent of the wheels' share, itself 3 % of the mass.
  double wheel_inertia_mass_kg = 0;
  double tire_radius_m = 0;  // the drive axle's, dynamic
  double final_drive = 0;
  double driveline_efficiency = 0;
  double engine_inertia_kgm2 = 0;  // EC1 SPN 1794 when the truck sends it
  double driveline_inertia_kgm2 = 0;
  double cda_prior_m2 = 0;
  double cda_sigma_m2 = 0;
  // Between CdA's error and the flywheel torque bias's: a CdA calibrated from two speeds took up
  // the engine-loss calibration's error, which the same truck carries into every later drive.
  double cda_torque_bias_correlation = 0.0;
  // How such a CdA moves with the ECU's torque scale: it was fitted to the drag of the torque the
  // ECU reports, so a scale error is partly in it too. The torque scale's second run
  // (torque_scale_consider.hpp) moves CdA with the scale by this much per unit of scale.
  double cda_per_torque_scale_m2 = 0.0;
  // The ECU's indicated torque (EEC1 against SPN 544) and the driveline's efficiency are known to
  // a share each, one sigma of a scale error (the vehicle file's torque_scale_sigma, and its
  // efficiency_sigma over the efficiency); the mass to its sigma (a scale ticket, a declared cargo).
  double torque_scale_sigma = 0.0;
  double efficiency_scale_sigma = 0.0;
  double mass_sigma_kg = 0.0;
  double crr_prior = 0.0055;
  double crr_sigma = 0.002;
  // Friction + accessories by engine speed from a standstill calibration; empty: EEC3's.
  EngineLossMap engine_losses;
};

TruckModel truck_model(const Vehicle& vehicle);

// What resists the motion, each positive against it (Eq. 2.2-2.4): the air on the truck's CdA at
// its airspeed, rolling on the tires' normal load, and the grade (its profile's value plus an error
// the filter carries). The one place the filter and the fuel breakdown take these forces from.
struct Resistances {
  double aero_n = 0, rolling_n = 0, grade_n = 0;
};
Resistances resistances(double mass_kg, double crr, double cda_m2, double air_density_kgpm3, double airspeed_mps, double grade_rad,
                        double grade_error_rad = 0.0);

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
  // The ECU's indicated torque at the wheels, before friction and parasitic losses come off: what
  // a scale error of EEC1's torque scales (at cruise it is about twice the tractive force).
  double indicated_force_n = 0;
  double air_density_kgpm3 = 1.2;
  double headwind_mps = 0;  // wind component blowing against the direction of travel
  double grade_rad = 0;
  double grade_sigma_rad = 0;  // the grade profile's uncertainty here
  double effective_mass_kg = 0;
  double wheel_force_per_flywheel_nm = 0;  // d(tractive force)/d(flywheel torque) in this gear, N per N m
  double crr_jump_variance = 0;            // CRR change allowed over this interval: axles crossing into a new cell
  double ripple_sigma_mps = 0;             // the road's roughness in the speed here (road_roughness.hpp)
  double ripple_correlation_m = 1.0;       // and the distance it stays correlated over
  bool usable = false;                     // false while braking, shifting or declutched
};

}  // namespace roadload::model
