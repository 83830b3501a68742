// One physics step of the truck: the forces at its start, the engine and driveline (cruise control
// or governor), the motion, the energy ledger and the quarter cars over the step.
#include <algorithm>
#include <cmath>
#include <numbers>

#include "plant_constants.hpp"
#include "roadload/sim/plant.hpp"
#include "roadload/sim/powertrain.hpp"
#include "roadload/sim/units.hpp"

namespace roadload::sim {

using namespace plant_detail;

// A clutch closing on a speed mismatch slips it away: the engine's kinetic energy jumps.
void TruckPlant::lock_clutch() {
  const double locked = engine_speed_radps(state_.speed_mps);
  const double before = state_.engine_rpm * kRadps_per_rpm;
  const double j_eng = truck_.engine.inertia_kgm2 + truck_.driveline.inertia_kgm2;
  const double slip_j = 0.5 * j_eng * (before * before - locked * locked);
  ledger_.clutch_j += slip_j;
  ledger_.kinetic_j -= slip_j;
  state_.engine_rpm = locked / kRadps_per_rpm;
}

// The forces resisting the motion at the start of the step, front axle at x0.
TruckPlant::Resisting TruckPlant::resisting(const Environment& env, double x0) {
  Resisting r;
  for (std::size_t i = 0; i < truck_.axles.size(); ++i) {
    const double fz = state_.axles[i].tire_force_n;
    state_.crr[i] = crr_of_axle(i, env);
    r.roll += state_.crr[i] * fz;
    r.fz_sum += fz;
    // The tire climbs the profile: the horizontal share of its vertical force feeds the
    // suspension's dissipation (dynamic rolling resistance).
    const double xa = x0 - truck_.axles[i].position_m;
    const double slope = (profile_.enveloped_height_m(xa + kSlopeBase_m) - profile_.enveloped_height_m(xa - kSlopeBase_m)) /
                         (2 * kSlopeBase_m);
    r.profile += fz * slope;
  }
  r.aero = aero_force_n(env);
  r.grade = mass_kg_ * kGravity_mps2 * std::sin(state_.grade_rad);
  r.brake = effects_.on(Effect::brake_drag) ? effects_.magnitude(Effect::brake_drag) : 0.0;
  return r;
}

// Friction, accessories and the fan load the crankshaft turning at omega0.
double TruckPlant::parasitic_torque_nm(double omega0) {
  const auto& acc = truck_.accessories;
  const double fan_speed = omega0 / (acc.fan_ref_rpm * kRadps_per_rpm);
  const double known_w = acc.alternator_w + acc.steering_w + acc.compressor_w + acc.fan_idle_w * fan_speed * fan_speed * fan_speed;
  const double fan_w = state_.fan_on ? (acc.fan_engaged_w - acc.fan_idle_w) * fan_speed * fan_speed * fan_speed : 0.0;
  const double omega_safe = std::max(omega0, 1.0);
  state_.friction_torque_nm = friction_torque_nm(truck_.engine, state_.engine_rpm);
  state_.ac_torque_nm = ac_power_w() / omega_safe;
  state_.accessory_torque_nm = known_w / omega_safe + state_.ac_torque_nm;
  state_.fan_torque_nm = fan_w / omega_safe;
  return state_.friction_torque_nm + state_.accessory_torque_nm + state_.fan_torque_nm;
}

// Cruise control: PI on speed, hunting around the set speed when that effect is on. Returns the
// tractive force; adds the service brake's force to `brake` when the engine cannot hold the speed.
double TruckPlant::cruise(double dt_s, double v0, double m_eff, double parasitic, const DrivelineLoss& loss, double& brake) {
  const double radius = truck_.drive_radius_m();
  double target = set_speed_mps_;
  if (effects_.on(Effect::cruise_hunting)) {
    target += effects_.magnitude(Effect::cruise_hunting) * std::sin(2 * std::numbers::pi * state_.t_s / 20.0);
  }
  const double err = target - v0;
  const double a_cmd = options_.cruise_kp_per_s * err + integrator_mps2_;
  const double wheel_nm = m_eff * a_cmd * radius;
  const double ind_cmd = clutch_torque_for_wheel_nm(truck_.driveline, loss, state_.gear, wheel_nm) + parasitic;
  const double ind_max = full_load_indicated_torque_nm(truck_.engine, state_.engine_rpm);
  state_.demand_torque_nm = std::clamp(ind_cmd, 0.0, ind_max);
  const bool saturated = ind_cmd > ind_max || (ind_cmd < 0 && v0 < target + kBrakeMargin_mps);
  if (!saturated) integrator_mps2_ += options_.cruise_ki_per_s2 * err * dt_s;
  state_.indicated_torque_nm += (state_.demand_torque_nm - state_.indicated_torque_nm) * std::min(1.0, dt_s / kTorqueLag_s);
  state_.clutch_torque_nm = state_.indicated_torque_nm - parasitic;
  const double tractive = wheel_torque_nm(truck_.driveline, loss, state_.gear, state_.clutch_torque_nm) / radius;
  if (ind_cmd < 0 && v0 > target + kBrakeMargin_mps) {
    const double wanted = -(ind_cmd - parasitic) * total_ratio(truck_.driveline, state_.gear) / radius;
    brake += std::max(0.0, wanted + tractive);
    state_.service_brake = true;
  }
  return tractive;
}

// Neutral or shifting: the governor brings the engine to idle (or the speed it is told to hold) or
// to the next gear's speed. Returns the engine's angular acceleration.
double TruckPlant::governor(double v0, double omega0, double parasitic) {
  const auto& e = truck_.engine;
  const double neutral_rpm = hold_rpm_ > 0 ? hold_rpm_ : e.idle_rpm;
  const double target_omega = shift_left_s_ > 0 ? total_ratio(truck_.driveline, target_gear_) * v0 / truck_.drive_radius_m()
                                                : neutral_rpm * kRadps_per_rpm;
  double omega_dot = (target_omega - omega0) / kGovernorTau_s;
  const double ind = parasitic + (e.inertia_kgm2 + truck_.driveline.inertia_kgm2) * omega_dot;
  if (ind < 0) omega_dot = -parasitic / (e.inertia_kgm2 + truck_.driveline.inertia_kgm2);
  state_.indicated_torque_nm = std::max(0.0, ind);
  state_.demand_torque_nm = state_.indicated_torque_nm;
  state_.clutch_torque_nm = 0;
  return omega_dot;
}

// The energy ledger, with the same discretisation as the motion. Returns the fuel burnt, J.
double TruckPlant::book(const Motion& m, const Resisting& r, double dt_s) {
  const double indicated_j = state_.indicated_torque_nm * m.omega_mean_dt;
  const double rpm_mean = m.omega_mean_dt / dt_s / kRadps_per_rpm;
  const double fuel_j = indicated_j > 0 ? indicated_j / indicated_efficiency(truck_.fuel, rpm_mean) : 0.0;
  ledger_.fuel_j += fuel_j;
  ledger_.thermal_j += fuel_j - indicated_j;
  ledger_.friction_j += state_.friction_torque_nm * m.omega_mean_dt;
  ledger_.accessories_j += state_.accessory_torque_nm * m.omega_mean_dt;
  ledger_.fan_j += state_.fan_torque_nm * m.omega_mean_dt;
  if (state_.clutch_engaged) {
    ledger_.driveline_j += state_.clutch_torque_nm * m.omega_mean_dt - m.tractive * m.dx;
  } else {
    const double j_eng = truck_.engine.inertia_kgm2 + truck_.driveline.inertia_kgm2;
    ledger_.kinetic_j += 0.5 * j_eng * (m.omega1 * m.omega1 - m.omega0 * m.omega0);
  }
  ledger_.roll_j += r.roll * m.dx;
  ledger_.aero_j += r.aero * m.dx;
  ledger_.grade_j += r.grade * m.dx;
  ledger_.profile_j += r.profile * m.dx;
  if (m.v0 > 0) ledger_.brake_j += r.brake * m.dx;
  ledger_.kinetic_j += 0.5 * m.m_eff * (m.v1 * m.v1 - m.v0 * m.v0);
  ledger_.distance_m += m.dx;
  if (m.v1 == 0.0 && m.v0 > 0) {
    // Stopping clipped the speed: the brake and resistances absorbed less than a full step.
    ledger_.kinetic_j += (m.tractive - m.resist) * m.dx - 0.5 * m.m_eff * (m.v1 * m.v1 - m.v0 * m.v0);
  }
  return fuel_j;
}

void TruckPlant::step(double dt_s, const Environment& env) {
  update_gear(dt_s);
  update_fan(dt_s);
  update_drafting(dt_s);
  Motion m;
  m.v0 = state_.speed_mps;
  const double x0 = state_.x_m;
  if (state_.clutch_engaged) lock_clutch();
  m.omega0 = state_.engine_rpm * kRadps_per_rpm;
  const double radius = truck_.drive_radius_m();
  state_.heading_deg = route_.heading_deg(x0);
  state_.grade_rad = route_.grade_rad(x0 - truck_.cg_position_m());
  Resisting r = resisting(env, x0);
  const double parasitic = parasitic_torque_nm(m.omega0);
  m.m_eff = effective_mass_kg();
  const DrivelineLoss loss = driveline_loss(truck_.driveline, state_.gear, effects_.on(Effect::driveline_losses),
                                            effects_.magnitude(Effect::driveline_losses));
  double omega_dot = 0;
  state_.service_brake = false;
  if (state_.clutch_engaged) {
    m.tractive = cruise(dt_s, m.v0, m.m_eff, parasitic, loss, r.brake);
  } else {
    omega_dot = governor(m.v0, m.omega0, parasitic);
  }
  // Explicit Euler on speed, trapezoid on position, so that every force's work F * dx sums
  // exactly to the change of kinetic energy.
  m.resist = r.roll + r.aero + r.grade + r.profile + (m.v0 > 0 ? r.brake : 0.0);
  m.v1 = m.v0 + dt_s * (m.tractive - m.resist) / m.m_eff;
  if (m.v1 < 0) m.v1 = 0;
  m.dx = 0.5 * (m.v0 + m.v1) * dt_s;
  const double x1 = x0 + m.dx;
  if (state_.clutch_engaged) {
    const double k = total_ratio(truck_.driveline, state_.gear) / radius;
    m.omega1 = k * m.v1;
    m.omega_mean_dt = k * m.dx;
  } else {
    m.omega1 = m.omega0 + omega_dot * dt_s;
    m.omega_mean_dt = 0.5 * (m.omega0 + m.omega1) * dt_s;
  }
  const double fuel_j = book(m, r, dt_s);
  step_vertical(dt_s, x0, x1);
  finish_step(dt_s, m, r, x1, fuel_j);
}

// Vertical motion over the same step, road heights under each axle at both ends.
void TruckPlant::step_vertical(double dt_s, double x0, double x1) {
  std::array<double, kMaxAxles> z0 = road_z_m_, z1{};
  for (std::size_t i = 0; i < truck_.axles.size(); ++i) {
    if (x0 != road_z_x_m_) z0[i] = road_height(i, x0);
    z1[i] = road_height(i, x1);
  }
  vertical_.step(dt_s, z0, z1);
  road_z_m_ = z1;
  road_z_x_m_ = x1;
}

void TruckPlant::finish_step(double dt_s, const Motion& m, const Resisting& r, double x1, double fuel_j) {
  state_.t_s += dt_s;
  state_.x_m = x1;
  state_.speed_mps = m.v1;
  state_.accel_mps2 = (m.v1 - m.v0) / dt_s;
  state_.engine_rpm = m.omega1 / kRadps_per_rpm;
  state_.fuel_kgps = fuel_j / truck_.fuel.lhv_jpkg / dt_s;
  state_.fuel_lph = fuel_rate_lph(truck_.fuel, state_.fuel_kgps);
  state_.tractive_n = m.tractive;
  state_.driveline_loss_n = state_.clutch_engaged && m.dx > 0 ? state_.clutch_torque_nm * m.omega_mean_dt / m.dx - m.tractive : 0.0;
  state_.roll_n = r.roll;
  state_.aero_n = r.aero;
  state_.grade_n = r.grade;
  state_.profile_n = r.profile;
  state_.brake_n = r.brake;
  state_.crr_mean = r.fz_sum > 0 ? r.roll / r.fz_sum : 0.0;
  for (std::size_t i = 0; i < truck_.axles.size(); ++i) state_.axles[i] = vertical_.outputs(i);
}

}  // namespace roadload::sim
