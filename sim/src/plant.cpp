#include "roadload/sim/plant.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "plant_constants.hpp"
#include "roadload/sim/air.hpp"
#include "roadload/sim/powertrain.hpp"
#include "roadload/sim/units.hpp"

namespace roadload::sim {

using namespace plant_detail;
namespace {

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
  double crr = route_.crr_at(state_.x_m - truck_.axles[axle].position_m) * truck_.tire_crr_scale;
  const auto& fx = effects_;
  if (fx.on(Effect::tire_warmup)) {
    crr *= 1.0 + fx.magnitude(Effect::tire_warmup) * tire_warmup_left(Seconds{state_.t_s} + options_.warm);
  }
  if (fx.on(Effect::temperature_crr)) crr *= 1.0 - fx.magnitude(Effect::temperature_crr) * (env.air_temp_c - 14.3);
  if (fx.on(Effect::speed_crr)) crr *= 1.0 + fx.magnitude(Effect::speed_crr) * (state_.speed_mps - 13.4112);
  if (fx.on(Effect::tire_pressure)) crr *= std::pow(1.0 + fx.magnitude(Effect::tire_pressure), -0.3);
  if (fx.on(Effect::wet_road)) crr *= 1.0 + kWetCrrPerMm * fx.magnitude(Effect::wet_road);
  if (fx.on(Effect::tread_wear)) crr *= 1.0 - kWornCrrDrop * fx.magnitude(Effect::tread_wear);
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
  road_z_m_ = z;
  road_z_x_m_ = x_m;
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
                      truck_.accessories.fan_idle_w + ac_power_w()) /
                     std::max(omega, 1.0);
  if (state_.clutch_engaged) {
    state_.indicated_torque_nm = clutch_torque_for_wheel_nm(d, loss, state_.gear, wheel_nm) +
                                 friction_torque_nm(truck_.engine, state_.engine_rpm) + acc;
  }
  ledger_ = EnergyLedger{};
}

}  // namespace roadload::sim
