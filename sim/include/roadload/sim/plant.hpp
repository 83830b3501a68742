#pragma once
// The truck as a physical system: longitudinal motion with the whole powertrain, one quarter car
// per axle on the road profile, and a cruise control driving it. Every force is kept in an energy
// ledger so that fuel energy in equals the work of every force plus every loss.
#include <array>
#include <limits>

#include "roadload/sim/air.hpp"
#include "roadload/sim/effects.hpp"
#include "roadload/sim/powertrain.hpp"
#include "roadload/sim/random.hpp"
#include "roadload/sim/road_profile.hpp"
#include "roadload/sim/route.hpp"
#include "roadload/sim/truck.hpp"
#include "roadload/sim/vertical.hpp"

namespace roadload::sim {

struct TruckState {
  double t_s = 0;
  double x_m = 0;  // front axle along the route
  double speed_mps = 0;
  double accel_mps2 = 0;  // dv/dt over the last step
  double heading_deg = 0;
  double grade_rad = 0;  // at the centre of gravity
  int gear = 0;          // 0: neutral or shifting
  bool clutch_engaged = false;
  double engine_rpm = 0;
  double indicated_torque_nm = 0;  // what J1939 calls actual engine torque
  double clutch_torque_nm = 0;     // brake torque delivered to the driveline
  double friction_torque_nm = 0;
  double accessory_torque_nm = 0;  // alternator, steering, compressor, idling fan
  double fan_torque_nm = 0;        // engaged fan beyond its idle drag
  double ac_torque_nm = 0;         // the part of accessory_torque_nm the A/C compressor takes (an effect)
  bool fan_on = false;
  double demand_torque_nm = 0;  // what the cruise control asked for, indicated
  double fuel_kgps = 0;
  double fuel_lph = 0;
  bool service_brake = false;
  double air_density_kgpm3 = 0;
  double airspeed_mps = 0;
  double yaw_rad = 0;
  // Forces at the wheels, positive when resisting motion (tractive positive when driving).
  double tractive_n = 0, roll_n = 0, aero_n = 0, grade_n = 0, profile_n = 0, brake_n = 0;
  double driveline_loss_n = 0;  // gearbox and axle losses, as a force at the wheels
  double crr_mean = 0;          // roll_n / sum of vertical tire forces
  std::array<double, kMaxAxles> crr{};
  std::array<AxleOutputs, kMaxAxles> axles{};
};

// Energy in joules since start. fuel = thermal + friction + accessories + fan + driveline
//  + roll + aero + grade + profile + brake + kinetic + clutch.
struct EnergyLedger {
  double fuel_j = 0, thermal_j = 0, friction_j = 0, accessories_j = 0, fan_j = 0, driveline_j = 0;
  double roll_j = 0, aero_j = 0, grade_j = 0, profile_j = 0, brake_j = 0;
  double kinetic_j = 0;  // change of the kinetic energy of the truck and everything that turns
  double clutch_j = 0;   // slip at gear changes
  double distance_m = 0;
};

struct PlantOptions {
  Seconds warm = kReportWarmUp;  // driving before the run starts (Scenario::driven_before)
  double cruise_kp_per_s = 0.3;
  double cruise_ki_per_s2 = 0.02;
};

class TruckPlant {
 public:
  TruckPlant(const TruckParams& truck, const Route& route, const RoadProfile& profile, const EffectSet& effects, std::uint64_t seed,
             PlantOptions options = {});

  // Places the truck at steady cruise: gear by the driver's rule, controller preloaded.
  void start(double x_m, double speed_mps, const Environment& env);
  void set_cruise_speed(double speed_mps) { set_speed_mps_ = speed_mps; }
  // Neutral coasting (coast-down tests): no engine torque, no brakes.
  void set_coasting(bool coasting) { coasting_ = coasting; }
  // In neutral, the governor holds this engine speed instead of idle (0: idle).
  void set_hold_rpm(double rpm) { hold_rpm_ = rpm; }

  void step(double dt_s, const Environment& env);

  const TruckState& state() const { return state_; }
  const EnergyLedger& ledger() const { return ledger_; }
  const TruckParams& truck() const { return truck_; }
  // Mass seen by the longitudinal motion in the current gear, rotating parts included.
  double effective_mass_kg() const;
  // The vertical system's energy since start, summed over axles (for the energy balance).
  AxleEnergy vertical_energy() const;
  double vertical_stored_energy_j() const;

 private:
  // One step's forces at its start, N, each positive against the motion.
  struct Resisting {
    double roll = 0, profile = 0, fz_sum = 0, aero = 0, grade = 0, brake = 0;
  };
  // One step's longitudinal motion: speeds, travel and the engine's turning.
  struct Motion {
    double v0 = 0, v1 = 0, dx = 0, m_eff = 0, tractive = 0, resist = 0;
    double omega0 = 0, omega1 = 0, omega_mean_dt = 0;
  };
  void lock_clutch();
  Resisting resisting(const Environment& env, double x0);
  double parasitic_torque_nm(double omega0);
  double ac_power_w() const { return effects_.on(Effect::ac_compressor) ? effects_.magnitude(Effect::ac_compressor) : 0.0; }
  double cruise(double dt_s, double v0, double m_eff, double parasitic, const DrivelineLoss& loss, double& brake);
  double governor(double v0, double omega0, double parasitic);
  double book(const Motion& m, const Resisting& r, double dt_s);
  void step_vertical(double dt_s, double x0, double x1);
  void finish_step(double dt_s, const Motion& m, const Resisting& r, double x1, double fuel_j);
  double engine_speed_radps(double speed_mps) const;
  double crr_of_axle(std::size_t axle, const Environment& env) const;
  double aero_force_n(const Environment& env);
  void update_gear(double dt_s);
  void update_fan(double dt_s);
  void update_drafting(double dt_s);
  double road_height(std::size_t axle, double x_front_m) const;

  TruckParams truck_;
  const Route& route_;
  const RoadProfile& profile_;
  EffectSet effects_;
  PlantOptions options_;
  Rng rng_;
  VerticalModel vertical_;
  TruckState state_;
  EnergyLedger ledger_;
  double set_speed_mps_ = 0;
  bool coasting_ = false;
  double hold_rpm_ = 0;
  double integrator_mps2_ = 0;
  double shift_left_s_ = 0;
  int target_gear_ = 0;
  double fan_left_s_ = 0;
  double draft_left_s_ = 0;
  double draft_reduction_ = 0;
  double mass_kg_ = 0;
  double wheel_inertia_mass_kg_ = 0;  // sum of J/r^2 of every wheel end
  // Road heights under the axles at the end of the last step, front axle at road_z_x_m_: the
  // next step starts there.
  std::array<double, kMaxAxles> road_z_m_{};
  double road_z_x_m_ = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace roadload::sim
