#include "roadload/sim/plant.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "roadload/sim/air.hpp"
#include "roadload/sim/powertrain.hpp"
#include "roadload/sim/units.hpp"

namespace roadload::sim {
namespace {

constexpr double kRadps_per_rpm = 2.0 * std::numbers::pi / 60.0;
constexpr double kDeg = 180.0 / std::numbers::pi;
constexpr double kSlopeBase_m = 0.05;  // half-width of the slope difference under a tire
constexpr double kTorqueLag_s = 0.1;   // fuelling and turbo response
constexpr double kGovernorTau_s = 0.3;
constexpr double kUpshift_rpm = 1650.0, kDownshift_rpm = 900.0, kMinCruise_rpm = 1000.0;
constexpr double kBrakeMargin_mps = 1.5;  // overspeed before the cruise control uses the service brake

std::vector<AxleParams> vertical_params(const TruckParams& t, const EffectSet& fx) {
  std::vector<AxleParams> p(t.axles.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    p[i] = t.axles[i].vertical;
    if (fx.on(Effect::suspension_friction)) {
      // Leaf springs rub; air springs barely (0.2 kN against 1.5 kN on the front leaf).
      p[i].coulomb_n = fx.magnitude(Effect::suspension_friction) * (i == 0 ? 1.0 : 0.13);
    }
    if (fx.on(Effect::tire_pressure)) p[i].k_tire_npm *= 1.0 + fx.magnitude(Effect::tire_pressure);
  }
  return p;
}

}  // namespace

TruckPlant::TruckPlant(const TruckParams& truck, const Route& route, const RoadProfile& profile, const EffectSet& effects,
                       std::uint64_t seed, PlantOptions options)
    : truck_(truck),
      route_(route),
      profile_(profile),
      effects_(effects),
      options_(options),
      rng_(seed, 0x504C414E54ULL),
      vertical_(vertical_params(truck, effects)) {
  mass_kg_ = truck_.total_mass_kg();
  for (const auto& a : truck_.axles) wheel_inertia_mass_kg_ += a.wheel_inertia_kgm2 / (a.tire_radius_m * a.tire_radius_m);
}

double TruckPlant::road_height(std::size_t axle, double x_front_m) const {
  return profile_.enveloped_height_m(x_front_m - truck_.axles[axle].position_m);
}

double TruckPlant::engine_speed_radps(double speed_mps) const {
  return total_ratio(truck_.driveline, state_.gear) * speed_mps / truck_.drive_radius_m();
}

double TruckPlant::effective_mass_kg() const {
  double m = mass_kg_ + wheel_inertia_mass_kg_;
  if (state_.clutch_engaged) {
    const double k = total_ratio(truck_.driveline, state_.gear) / truck_.drive_radius_m();
    m += (truck_.engine.inertia_kgm2 + truck_.driveline.inertia_kgm2) * k * k;
  }
  return m;
}

AxleEnergy TruckPlant::vertical_energy() const {
  AxleEnergy sum;
  for (std::size_t i = 0; i < truck_.axles.size(); ++i) {
    const AxleEnergy& e = vertical_.energy(i);
    sum.road_work_j += e.road_work_j;
    sum.damper_j += e.damper_j;
    sum.friction_j += e.friction_j;
    sum.tire_j += e.tire_j;
  }
  return sum;
}

double TruckPlant::vertical_stored_energy_j() const {
  double e = 0;
  for (std::size_t i = 0; i < truck_.axles.size(); ++i) e += vertical_.stored_energy_j(i);
  return e;
}

double TruckPlant::crr_of_axle(std::size_t axle, const Environment& env) const {
  double crr = route_.crr_at(state_.x_m - truck_.axles[axle].position_m);
  const auto& fx = effects_;
  if (fx.on(Effect::tire_warmup)) {
    crr *= 1.0 + fx.magnitude(Effect::tire_warmup) * std::exp(-(state_.t_s + options_.warm.count()) / 1200.0);
  }
  if (fx.on(Effect::temperature_crr)) crr *= 1.0 - fx.magnitude(Effect::temperature_crr) * (env.air_temp_c - 14.3);
  if (fx.on(Effect::speed_crr)) crr *= 1.0 + fx.magnitude(Effect::speed_crr) * (state_.speed_mps - 13.4112);
  if (fx.on(Effect::tire_pressure)) crr *= std::pow(1.0 + fx.magnitude(Effect::tire_pressure), -0.3);
  return crr;
}

double TruckPlant::aero_force_n(const Environment& env) {
  const RelativeWind w = relative_wind(state_.speed_mps, state_.heading_deg, env.wind_speed_mps, env.wind_from_deg);
  state_.air_density_kgpm3 = air_density_kgpm3(env.pressure_pa, env.air_temp_c);
  state_.airspeed_mps = w.airspeed_mps;
  state_.yaw_rad = w.yaw_rad;
  double cda = truck_.cda_m2 * (1.0 - draft_reduction_);
  double v2 = w.airspeed_mps * std::abs(w.airspeed_mps);
  if (effects_.on(Effect::yaw_drag)) {
    // Drag on the resultant relative wind grows with yaw; linear beyond 10 degrees.
    const double a = effects_.magnitude(Effect::yaw_drag);
    const double psi = std::abs(w.yaw_rad) * kDeg;
    const double gain = psi <= 10.0 ? a * psi * psi : a * (100.0 + 20.0 * (psi - 10.0));
    cda *= 1.0 + gain;
    const double cross = w.airspeed_mps * std::tan(w.yaw_rad);
    v2 = std::copysign(w.airspeed_mps * w.airspeed_mps + cross * cross, w.airspeed_mps);
  }
  return 0.5 * state_.air_density_kgpm3 * cda * v2;
}

void TruckPlant::update_fan(double dt_s) {
  if (!effects_.on(Effect::fan_engagement)) return;
  // A thermostat cycle seen as a random telegraph: on for 40 s on average, off so the duty fits.
  const double duty = std::clamp(effects_.magnitude(Effect::fan_engagement), 0.01, 0.99);
  fan_left_s_ -= dt_s;
  if (fan_left_s_ > 0) return;
  state_.fan_on = !state_.fan_on;
  const double mean = state_.fan_on ? 40.0 : 40.0 * (1.0 - duty) / duty;
  fan_left_s_ = -mean * std::log(rng_.uniform());
}

void TruckPlant::update_drafting(double dt_s) {
  if (!effects_.on(Effect::drafting)) return;
  // Episodes of following traffic (40 s on average, 120 s apart) at a gap of 15-60 m.
  draft_left_s_ -= dt_s;
  if (draft_left_s_ <= 0) {
    const bool following = draft_reduction_ == 0.0;
    draft_left_s_ = -(following ? 40.0 : 120.0) * std::log(rng_.uniform());
    draft_reduction_ = following ? effects_.magnitude(Effect::drafting) * std::exp(-rng_.uniform(15.0, 60.0) / 40.0) : 0.0;
  }
}

void TruckPlant::update_gear(double dt_s) {
  const auto& d = truck_.driveline;
  if (coasting_) {
    state_.gear = 0;
    state_.clutch_engaged = false;
    return;
  }
  if (shift_left_s_ > 0) {
    shift_left_s_ -= dt_s;
    if (shift_left_s_ <= 0) {
      state_.gear = target_gear_;
      state_.clutch_engaged = true;
    }
    return;
  }
  if (!state_.clutch_engaged) return;
  const double rpm = engine_speed_radps(state_.speed_mps) / kRadps_per_rpm;
  const int top = static_cast<int>(d.gear_ratios.size());
  int next = state_.gear;
  if (rpm > kUpshift_rpm && state_.gear < top) next = state_.gear + 1;
  if (rpm < kDownshift_rpm && state_.gear > 1) next = state_.gear - 1;
  if (next != state_.gear) {
    target_gear_ = next;
    shift_left_s_ = d.shift_time.count();
    state_.gear = 0;
    state_.clutch_engaged = false;
  }
}

void TruckPlant::start(double x_m, double speed_mps, const Environment& env) {
  state_ = TruckState{};
  state_.x_m = x_m;
  state_.speed_mps = speed_mps;
  set_speed_mps_ = speed_mps;
  const auto& d = truck_.driveline;
  state_.gear = 1;
  for (int g = static_cast<int>(d.gear_ratios.size()); g >= 1; --g) {
    const double rpm = total_ratio(d, g) * speed_mps / truck_.drive_radius_m() / kRadps_per_rpm;
    if (rpm >= kMinCruise_rpm) {
      state_.gear = g;
      break;
    }
  }
  state_.clutch_engaged = !coasting_;
  if (coasting_) state_.gear = 0;
  const Route::Position p = route_.at(x_m);
  state_.heading_deg = p.heading_deg;
  state_.engine_rpm = state_.clutch_engaged ? engine_speed_radps(speed_mps) / kRadps_per_rpm : truck_.engine.idle_rpm;
  std::array<double, kMaxAxles> z{};
  for (std::size_t i = 0; i < truck_.axles.size(); ++i) z[i] = road_height(i, x_m);
  vertical_.reset(z);
  for (std::size_t i = 0; i < truck_.axles.size(); ++i) state_.axles[i] = vertical_.outputs(i);
  // Preload the controller with the steady force so the run starts at cruise, not in a transient.
  const double cg = truck_.cg_position_m();
  state_.grade_rad = route_.grade_rad(x_m - cg);
  double roll = 0;
  for (std::size_t i = 0; i < truck_.axles.size(); ++i) roll += crr_of_axle(i, env) * state_.axles[i].tire_force_n;
  const double steady = roll + aero_force_n(env) + mass_kg_ * kGravity_mps2 * std::sin(state_.grade_rad);
  integrator_mps2_ = steady / effective_mass_kg();
  const double wheel_nm = steady * truck_.drive_radius_m();
  const DrivelineLoss loss = driveline_loss(d, state_.gear, effects_.on(Effect::driveline_losses),
                                            effects_.magnitude(Effect::driveline_losses));
  const double omega = state_.engine_rpm * kRadps_per_rpm;
  const double acc = (truck_.accessories.alternator_w + truck_.accessories.steering_w + truck_.accessories.compressor_w +
                      truck_.accessories.fan_idle_w) / std::max(omega, 1.0);
  if (state_.clutch_engaged) {
    state_.indicated_torque_nm = clutch_torque_for_wheel_nm(d, loss, state_.gear, wheel_nm) +
                                 friction_torque_nm(truck_.engine, state_.engine_rpm) + acc;
  }
  ledger_ = EnergyLedger{};
}

void TruckPlant::step(double dt_s, const Environment& env) {
  const auto& e = truck_.engine;
  const auto& acc = truck_.accessories;
  update_gear(dt_s);
  update_fan(dt_s);
  update_drafting(dt_s);

  const double v0 = state_.speed_mps;
  const double x0 = state_.x_m;
  if (state_.clutch_engaged) {
    // A clutch closing on a speed mismatch slips it away: the engine's kinetic energy jumps.
    const double locked = engine_speed_radps(v0);
    const double before = state_.engine_rpm * kRadps_per_rpm;
    const double j_eng = e.inertia_kgm2 + truck_.driveline.inertia_kgm2;
    const double slip_j = 0.5 * j_eng * (before * before - locked * locked);
    ledger_.clutch_j += slip_j;
    ledger_.kinetic_j -= slip_j;
    state_.engine_rpm = locked / kRadps_per_rpm;
  }
  const double omega0 = state_.engine_rpm * kRadps_per_rpm;
  const double radius = truck_.drive_radius_m();
  const Route::Position pos = route_.at(x0);
  state_.heading_deg = pos.heading_deg;
  const double cg = truck_.cg_position_m();
  state_.grade_rad = route_.grade_rad(x0 - cg);

  // Resisting forces at the start of the step.
  double roll = 0, profile = 0, fz_sum = 0;
  for (std::size_t i = 0; i < truck_.axles.size(); ++i) {
    const double fz = state_.axles[i].tire_force_n;
    state_.crr[i] = crr_of_axle(i, env);
    roll += state_.crr[i] * fz;
    fz_sum += fz;
    // The tire climbs the profile: the horizontal share of its vertical force feeds the
    // suspension's dissipation (dynamic rolling resistance).
    const double xa = x0 - truck_.axles[i].position_m;
    const double slope = (profile_.enveloped_height_m(xa + kSlopeBase_m) - profile_.enveloped_height_m(xa - kSlopeBase_m)) /
                         (2 * kSlopeBase_m);
    profile += fz * slope;
  }
  const double aero = aero_force_n(env);
  const double grade = mass_kg_ * kGravity_mps2 * std::sin(state_.grade_rad);
  double brake = effects_.on(Effect::brake_drag) ? effects_.magnitude(Effect::brake_drag) : 0.0;

  // Accessories and the fan load the crankshaft.
  const double fan_speed = omega0 / (acc.fan_ref_rpm * kRadps_per_rpm);
  const double known_w = acc.alternator_w + acc.steering_w + acc.compressor_w + acc.fan_idle_w * fan_speed * fan_speed * fan_speed;
  const double fan_w = state_.fan_on ? (acc.fan_engaged_w - acc.fan_idle_w) * fan_speed * fan_speed * fan_speed : 0.0;
  const double omega_safe = std::max(omega0, 1.0);
  state_.friction_torque_nm = friction_torque_nm(e, state_.engine_rpm);
  state_.accessory_torque_nm = known_w / omega_safe;
  state_.fan_torque_nm = fan_w / omega_safe;
  const double parasitic = state_.friction_torque_nm + state_.accessory_torque_nm + state_.fan_torque_nm;

  const double m_eff = effective_mass_kg();
  const DrivelineLoss loss = driveline_loss(truck_.driveline, state_.gear, effects_.on(Effect::driveline_losses),
                                            effects_.magnitude(Effect::driveline_losses));
  double tractive = 0;
  double omega_dot = 0;
  state_.service_brake = false;
  if (state_.clutch_engaged) {
    // Cruise control: PI on speed, hunting around the set speed when that effect is on.
    double target = set_speed_mps_;
    if (effects_.on(Effect::cruise_hunting)) {
      target += effects_.magnitude(Effect::cruise_hunting) * std::sin(2 * std::numbers::pi * state_.t_s / 20.0);
    }
    const double err = target - v0;
    const double a_cmd = options_.cruise_kp_per_s * err + integrator_mps2_;
    const double wheel_nm = m_eff * a_cmd * radius;
    const double ind_cmd = clutch_torque_for_wheel_nm(truck_.driveline, loss, state_.gear, wheel_nm) + parasitic;
    const double ind_max = full_load_indicated_torque_nm(e, state_.engine_rpm);
    state_.demand_torque_nm = std::clamp(ind_cmd, 0.0, ind_max);
    const bool saturated = ind_cmd > ind_max || (ind_cmd < 0 && v0 < target + kBrakeMargin_mps);
    if (!saturated) integrator_mps2_ += options_.cruise_ki_per_s2 * err * dt_s;
    state_.indicated_torque_nm += (state_.demand_torque_nm - state_.indicated_torque_nm) * std::min(1.0, dt_s / kTorqueLag_s);
    state_.clutch_torque_nm = state_.indicated_torque_nm - parasitic;
    tractive = wheel_torque_nm(truck_.driveline, loss, state_.gear, state_.clutch_torque_nm) / radius;
    if (ind_cmd < 0 && v0 > target + kBrakeMargin_mps) {
      const double wanted = -(ind_cmd - parasitic) * total_ratio(truck_.driveline, state_.gear) / radius;
      brake += std::max(0.0, wanted + tractive);
      state_.service_brake = true;
    }
  } else {
    // Neutral or shifting: the governor brings the engine to idle (or the speed it is told to
    // hold) or to the next gear's speed.
    const double neutral_rpm = hold_rpm_ > 0 ? hold_rpm_ : e.idle_rpm;
    const double target_omega = shift_left_s_ > 0 ? total_ratio(truck_.driveline, target_gear_) * v0 / radius
                                                  : neutral_rpm * kRadps_per_rpm;
    omega_dot = (target_omega - omega0) / kGovernorTau_s;
    const double ind = parasitic + (e.inertia_kgm2 + truck_.driveline.inertia_kgm2) * omega_dot;
    if (ind < 0) omega_dot = -parasitic / (e.inertia_kgm2 + truck_.driveline.inertia_kgm2);
    state_.indicated_torque_nm = std::max(0.0, ind);
    state_.demand_torque_nm = state_.indicated_torque_nm;
    state_.clutch_torque_nm = 0;
  }

  // Semi-implicit in nothing: explicit Euler on speed, trapezoid on position, so that every
  // force's work F * dx sums exactly to the change of kinetic energy.
  const double resist = roll + aero + grade + profile + (v0 > 0 ? brake : 0.0);
  double v1 = v0 + dt_s * (tractive - resist) / m_eff;
  if (v1 < 0) v1 = 0;
  const double dx = 0.5 * (v0 + v1) * dt_s;
  const double x1 = x0 + dx;

  double omega1 = 0, omega_mean_dt = 0;
  if (state_.clutch_engaged) {
    const double k = total_ratio(truck_.driveline, state_.gear) / radius;
    omega1 = k * v1;
    omega_mean_dt = k * dx;
  } else {
    omega1 = omega0 + omega_dot * dt_s;
    omega_mean_dt = 0.5 * (omega0 + omega1) * dt_s;
  }

  // Energy ledger, with the same discretisation as the motion.
  const double indicated_j = state_.indicated_torque_nm * omega_mean_dt;
  const double rpm_mean = omega_mean_dt / dt_s / kRadps_per_rpm;
  const double fuel_j = indicated_j > 0 ? indicated_j / indicated_efficiency(truck_.fuel, rpm_mean) : 0.0;
  ledger_.fuel_j += fuel_j;
  ledger_.thermal_j += fuel_j - indicated_j;
  ledger_.friction_j += state_.friction_torque_nm * omega_mean_dt;
  ledger_.accessories_j += state_.accessory_torque_nm * omega_mean_dt;
  ledger_.fan_j += state_.fan_torque_nm * omega_mean_dt;
  if (state_.clutch_engaged) {
    ledger_.driveline_j += state_.clutch_torque_nm * omega_mean_dt - tractive * dx;
  } else {
    const double j_eng = e.inertia_kgm2 + truck_.driveline.inertia_kgm2;
    ledger_.kinetic_j += 0.5 * j_eng * (omega1 * omega1 - omega0 * omega0);
  }
  ledger_.roll_j += roll * dx;
  ledger_.aero_j += aero * dx;
  ledger_.grade_j += grade * dx;
  ledger_.profile_j += profile * dx;
  if (v0 > 0) ledger_.brake_j += brake * dx;
  ledger_.kinetic_j += 0.5 * m_eff * (v1 * v1 - v0 * v0);
  ledger_.distance_m += dx;
  if (v1 == 0.0 && v0 > 0) {
    // Stopping clipped the speed: the brake and resistances absorbed less than a full step.
    ledger_.kinetic_j += (tractive - resist) * dx - 0.5 * m_eff * (v1 * v1 - v0 * v0);
  }

  // Vertical motion over the same step, road heights under each axle at both ends.
  std::array<double, kMaxAxles> z0{}, z1{};
  for (std::size_t i = 0; i < truck_.axles.size(); ++i) {
    z0[i] = road_height(i, x0);
    z1[i] = road_height(i, x1);
  }
  vertical_.step(dt_s, z0, z1);

  state_.t_s += dt_s;
  state_.x_m = x1;
  state_.speed_mps = v1;
  state_.accel_mps2 = (v1 - v0) / dt_s;
  state_.engine_rpm = omega1 / kRadps_per_rpm;
  state_.fuel_kgps = fuel_j / truck_.fuel.lhv_jpkg / dt_s;
  state_.fuel_lph = fuel_rate_lph(truck_.fuel, state_.fuel_kgps);
  state_.tractive_n = tractive;
  state_.driveline_loss_n = state_.clutch_engaged && dx > 0 ? state_.clutch_torque_nm * omega_mean_dt / dx - tractive : 0.0;
  state_.roll_n = roll;
  state_.aero_n = aero;
  state_.grade_n = grade;
  state_.profile_n = profile;
  state_.brake_n = brake;
  state_.crr_mean = fz_sum > 0 ? roll / fz_sum : 0.0;
  for (std::size_t i = 0; i < truck_.axles.size(); ++i) state_.axles[i] = vertical_.outputs(i);
}

}  // namespace roadload::sim
