#pragma once
// Engine, fuel map and driveline of the plant. Torque convention as J1939 reports it: the engine's
// *indicated* torque covers friction, accessories and the brake torque delivered to the clutch.
#include "roadload/sim/truck.hpp"

namespace roadload::sim {

double full_load_indicated_torque_nm(const EngineSpec& e, double rpm);
double friction_torque_nm(const EngineSpec& e, double rpm);

// Indicated efficiency of the Willans-form map; fuel power = indicated power / efficiency.
double indicated_efficiency(const FuelSpec& f, double rpm);
double fuel_rate_kgps(const FuelSpec& f, double indicated_power_w, double rpm);
double fuel_rate_lph(const FuelSpec& f, double fuel_kgps);

// Mechanical loss of the gearbox and axle between clutch and wheels, as torque at the wheels.
struct DrivelineLoss {
  double efficiency = 1.0;     // proportional (mesh) part
  double spin_wheel_nm = 0.0;  // load-independent churning and bearing drag, at the wheels
};

// The driveline-efficiency effect switches from the single efficiency to gear- and load-dependent
// losses; `spin_scale` scales the churning losses (1 = the parameter sheet's values).
DrivelineLoss driveline_loss(const DrivelineSpec& d, int gear, bool detailed, double spin_scale);

// Wheel torque from clutch torque through the losses: they always oppose the power flow.
double wheel_torque_nm(const DrivelineSpec& d, const DrivelineLoss& loss, int gear, double clutch_torque_nm);
double clutch_torque_for_wheel_nm(const DrivelineSpec& d, const DrivelineLoss& loss, int gear, double wheel_torque_nm);

double total_ratio(const DrivelineSpec& d, int gear);  // gear 1..10; 0 is neutral

}  // namespace roadload::sim
