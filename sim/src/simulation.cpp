#include "roadload/sim/simulation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "roadload/content_hash.hpp"
#include "roadload/sim/j1939_bus.hpp"
#include "roadload/sim/powertrain.hpp"
#include "roadload/sim/road_builder.hpp"
#include "roadload/sim/sensors.hpp"
#include "roadload/sim/units.hpp"
#include "roadload/sim/wind.hpp"

namespace roadload::sim {
namespace {

constexpr double kOdometerStart_m = 412345600.0;
constexpr std::uint8_t kWeatherStationId = 100;
constexpr std::uint8_t kGnssId = 200;

// Independent random streams per consumer, so adding one does not shift another.
enum Stream : std::uint64_t { kWind = 2, kBus, kGnss, kMast, kVp1, kAccelBase = 100 };

Route build_route(const Scenario& s) {
  auto r = Route::build(s.route);
  // load_scenario has built it once already: only a scenario assembled in code can fail here.
  if (!r) {
    std::fprintf(stderr, "roadload: scenario %s: %s\n", s.name.c_str(), r.error().to_string().c_str());
    std::abort();
  }
  return std::move(r.value());
}

TruckParams scenario_truck(const Scenario& s) {
  TruckParams t = truck_from_vehicle(s.vehicle, s.unsprung);
  for (auto& a : t.axles) {
    a.vertical.sprung_kg += (s.load_scale - 1.0) * a.load_kg;
    a.load_kg *= s.load_scale;
  }
  t.cda_m2 *= s.cda_scale;
  t.tire_crr_scale = s.tire_crr_scale;
  t.engine.friction_a_pct *= s.engine_friction_scale;
  t.engine.friction_b_pct *= s.engine_friction_scale;
  t.engine.friction_c_pct *= s.engine_friction_scale;
  for (double* w : {&t.accessories.alternator_w, &t.accessories.steering_w, &t.accessories.compressor_w, &t.accessories.fan_engaged_w,
                    &t.accessories.fan_idle_w}) {
    *w *= s.accessory_scale;
  }
  for (auto& a : t.axles) {
    a.tire_radius_m *= s.tire_radius_scale;
    if (s.effects.on(Effect::tread_wear)) a.tire_radius_m -= kUsableTread_m * s.effects.magnitude(Effect::tread_wear);
  }
  return t;
}

// The ECUs turn wheel revolutions into speed and distance with the vehicle file's tire radius:
// on other or worn tires they read off by this factor, and the cruise control holds the
// speed they read.
double speedometer_scale(const Scenario& s, const TruckParams& worn) {
  return truck_from_vehicle(s.vehicle, s.unsprung).drive_radius_m() / worn.drive_radius_m();
}

// The driver's set speed at x: the crawl over the last crawl_m before each stop line, and before it
// a steady 1 m/s^2 of braking down to the crawl (the driver's, not the cruise control's).
double set_speed_mps(const Scenario& sc, double x_m) {
  constexpr double kBraking_mps2 = 1.0;
  const double into_block = std::fmod(std::max(0.0, x_m - sc.start_m), sc.stops.every_m);
  const double to_crawl_m = sc.stops.every_m - sc.stops.crawl_m - into_block;
  if (to_crawl_m <= 0) return sc.stops.crawl_mps;
  return std::min(sc.speed_mps, std::sqrt(sc.stops.crawl_mps * sc.stops.crawl_mps + 2 * kBraking_mps2 * to_crawl_m));
}

BusOptions bus_options(const ClockSpec& c) {
  BusOptions o;
  o.rx_latency = c.can_rx_latency;
  o.rx_jitter = c.can_rx_jitter;
  o.ecu_drift_ppm = c.ecu_drift_ppm;
  return o;
}

}  // namespace

struct Simulation::Parts {
  Parts(const Scenario& sc, std::uint64_t sd, const j1939::Database& db)
      : scenario(sc),
        seed(sd),
        route(build_route(sc)),
        profile(build_road(sc, route)),
        truck(scenario_truck(sc)),
        speedometer(speedometer_scale(sc, truck)),
        plant(truck, route, profile, sc.effects, sd, PlantOptions{.warm = sc.driven_before}),
        wind(sc.weather, sc.effects.magnitude(Effect::wind_gusts), Rng(sd, kWind)),
        bus(db, bus_options(sc.clocks), Rng(sd, kBus)),
        gnss(sc.gnss_rate_hz, sc.start_utc_ns, sc.clocks.gnss_latency.count(), sc.effects.magnitude(Effect::gnss_elevation_bias),
             Rng(sd, kGnss)),
        mast(sc.effects.magnitude(Effect::air_density_error), sc.clocks.weather_offset.count(), Rng(sd, kMast)),
        vp1_rng(sd, kVp1) {
    const auto mounts = accel_mounts(truck, sc.accelerometers);
    for (std::size_t i = 0; i < mounts.size(); ++i) {
      accels.emplace_back(static_cast<std::uint8_t>(i), mounts[i], sc.accel_rate_hz, Rng(sd, kAccelBase + i));
    }
  }

  BusView view(const TruckState& s, const Environment& env) {
    const auto& e = truck.engine;
    const double ref = e.reference_torque_nm;
    BusView v;
    const double bias = scenario.effects.magnitude(Effect::torque_bias);
    v.engine_rpm = s.engine_rpm;
    v.actual_torque_pct = s.indicated_torque_nm * (1.0 + bias) / ref * 100.0;
    v.demand_torque_pct = s.demand_torque_nm / ref * 100.0;
    v.friction_torque_pct = s.friction_torque_nm / ref * 100.0;
    // The engine's estimate knows its own accessories, not a compressor the cab switched on.
    v.parasitic_torque_pct = (s.accessory_torque_nm - s.ac_torque_nm) / ref * 100.0;
    const double max = full_load_indicated_torque_nm(e, s.engine_rpm);
    v.load_pct = max > 0 ? std::clamp(s.indicated_torque_nm / max * 100.0, 0.0, 125.0) : 0.0;
    v.engine_controlled = s.clutch_engaged;
    v.wheel_speed_kmh = s.speed_mps * speedometer * 3.6;
    v.front_axle_speed_kmh = s.speed_mps * speedometer * 3.6;
    v.cruise_active = s.clutch_engaged && !scenario.coast;
    v.cruise_set_kmh = scenario.speed_mps * 3.6;
    v.brake_switch = s.service_brake;
    v.clutch_switch = !s.clutch_engaged && !scenario.coast;
    v.fuel_lph = s.fuel_lph;
    v.gear = s.gear;
    v.selected_gear = s.gear;
    v.gear_ratio = s.gear > 0 ? truck.driveline.gear_ratios[static_cast<std::size_t>(s.gear - 1)] : 0.0;
    v.driveline_engaged = s.clutch_engaged;
    v.shift_in_process = !s.clutch_engaged && !scenario.coast;
    v.output_shaft_rpm = s.speed_mps / truck.drive_radius_m() * truck.driveline.final_drive * 60.0 / (2 * std::numbers::pi);
    v.pressure_kpa = env.pressure_pa / 1000.0;
    v.ambient_c = env.air_temp_c + 0.3;  // the truck's sensor sits near warm parts
    v.intake_c = env.air_temp_c + 5.0;
    v.total_distance_m = kOdometerStart_m + plant.ledger().distance_m * speedometer;
    v.trip_distance_m = plant.ledger().distance_m * speedometer;
    v.lat_deg = vp1_lat;
    v.lon_deg = vp1_lon;
    v.fan_on = s.fan_on;
    v.fan_rpm = s.engine_rpm * 1.2 * (s.fan_on ? 1.0 : 0.08);
    v.coolant_c = s.fan_on ? 95.0 : 88.0;
    v.ref_torque_nm = ref;
    v.idle_rpm = e.idle_rpm;
    v.high_idle_rpm = e.full_load_rpm.back();
    v.inertia_kgm2 = e.inertia_kgm2;
    for (std::size_t i = 0; i < 5; ++i) {
      v.ec1_rpm[i] = e.full_load_rpm[i];
      v.ec1_pct[i] = e.full_load_fraction[i] * 100.0;
    }
    return v;
  }

  Kinematics kinematics(const TruckState& s) const {
    Kinematics k;
    k.t_s = s.t_s;
    k.accel_long_mps2 = s.accel_mps2;
    k.gravity_along_mps2 = kGravity_mps2 * std::sin(s.grade_rad);
    k.gravity_normal_mps2 = kGravity_mps2 * std::cos(s.grade_rad);
    for (std::size_t i = 0; i < truck.axles.size(); ++i) {
      k.sprung_mps2[i] = s.axles[i].sprung_accel_mps2;
      k.unsprung_mps2[i] = s.axles[i].unsprung_accel_mps2;
    }
    return k;
  }

  // Capture stamp of an accelerometer sample taken at true time t: the scenario's clock offset
  // and drift, plus the CAN-accelerometer offset effect (late, drifting 20 ppm).
  double accel_stamp(double t_s) const {
    const ClockSpec& c = scenario.clocks;
    double stamp = t_s + c.accel_offset.count() + c.accel_drift_ppm * 1e-6 * t_s;
    if (scenario.effects.on(Effect::can_accel_offset)) {
      stamp += scenario.effects.magnitude(Effect::can_accel_offset) + 20e-6 * t_s;
    }
    return std::max(stamp, 0.0);
  }

  // Accelerometers in true-time order across parts, up to the plant's time.
  void sample_accels(const Kinematics& before, const Kinematics& now, SampleSink& sink, RunSummary& sum) {
    const double until_s = plant.state().t_s;
    for (;;) {
      Accelerometer* next = nullptr;
      for (auto& a : accels) {
        if (a.next_true_s() <= until_s && (next == nullptr || a.next_true_s() < next->next_true_s())) next = &a;
      }
      if (next == nullptr) break;
      const double t = next->next_true_s();
      sink.accel(next->sample(before, now, accel_stamp(t)));
      ++sum.accel_samples;
    }
  }

  // The receiver's fixes over the last step, the antenna placed between its two ends.
  void sample_gnss(double t_before_s, double dt, double x_before, double v_before, SampleSink& sink, RunSummary& sum) {
    const TruckState& s = plant.state();
    while (gnss.next_true_s() <= s.t_s) {
      const double t = gnss.next_true_s();
      const double w = (t - t_before_s) / dt;
      const double x = x_before + w * (s.x_m - x_before);
      const Route::Position pos = route.at(x - truck.gnss_antenna_behind_front_m);
      const GnssTruth g{t,
                        pos.lat_deg,
                        pos.lon_deg,
                        pos.elev_m + truck.gnss_antenna_height_m,
                        v_before + w * (s.speed_mps - v_before),
                        pos.heading_deg};
      GnssFix fix = gnss.fix(g);
      sink.gnss(fix);
      ++sum.gnss_fixes;
    }
  }

  void sample_weather(double dt, SampleSink& sink, RunSummary& sum) {
    mast.observe(wind.at_mast(), dt);
    WeatherSample ws;
    while (mast.sample(plant.state().t_s, ws)) {
      ws.station = static_cast<std::uint8_t>(ws.station + kWeatherStationId);
      sink.weather(ws);
      ++sum.weather_samples;
    }
  }

  // The truck's own 1 Hz GPS feeds VP1: metres of noise, no DGPS.
  void update_vp1() {
    const TruckState& s = plant.state();
    if (s.t_s < vp1_next_s) return;
    const Route::Position pos = route.at(s.x_m - truck.gnss_antenna_behind_front_m);
    vp1_lat = pos.lat_deg + 2.5 * vp1_rng.normal() / 111132.0;
    vp1_lon = pos.lon_deg + 2.5 * vp1_rng.normal() / (111320.0 * std::cos(pos.lat_deg * std::numbers::pi / 180.0));
    vp1_next_s += 1.0;
  }

  Scenario scenario;
  std::uint64_t seed;
  Route route;
  RoadProfile profile;
  TruckParams truck;
  double speedometer;
  TruckPlant plant;
  WindField wind;
  J1939Bus bus;
  GnssReceiver gnss;
  WeatherMast mast;
  std::vector<Accelerometer> accels;
  Rng vp1_rng;
  double vp1_lat = 0, vp1_lon = 0, vp1_next_s = 0;
};

Simulation::Simulation(const Scenario& scenario, std::uint64_t seed, const j1939::Database& db)
    : p_(std::make_unique<Parts>(scenario, seed, db)) {}

Simulation::~Simulation() = default;

const TruckPlant& Simulation::plant() const { return p_->plant; }
const Route& Simulation::route() const { return p_->route; }

recording::Metadata Simulation::metadata() const {
  const Scenario& sc = p_->scenario;
  recording::Metadata m;
  m.created_by = "roadload simulate";
  // A logger draws its run's id at random; a simulated run's is a hash of what makes it this run (scenario, seed, truck, effects;
  // the driving before it only off its default, so older runs keep their ids): the same run simulated again is the same drive.
  std::string identity = sc.name + "\n" + sc.source + "\n" + std::to_string(p_->seed) + "\n" + std::to_string(sc.start_utc_ns) +
                         "\n" + sc.vehicle.name + "\n" + p_->truck.vin + "\n" + std::to_string(sc.speed_mps) + "\n" +
                         std::to_string(sc.duration ? sc.duration->count() : -1.0);
  for (double v : {sc.load_scale, sc.engine_friction_scale, sc.accessory_scale, sc.cda_scale, sc.tire_radius_scale, sc.start_m,
                   sc.end_m, sc.weather.air_temp_c})
    identity += "," + std::to_string(v);
  if (sc.driven_before != kReportWarmUp) identity += "\ndriven " + std::to_string(sc.driven_before.count());
  for (const auto& e : effect_catalog()) {
    if (sc.effects.on(e.id)) identity += "\n" + std::string(e.name) + "=" + std::to_string(sc.effects.magnitude(e.id));
  }
  m.recording_id = "sim-" + content_hash(identity).substr(8);
  m.clock_source = "simulated";
  m.utc_offset_ns = sc.start_utc_ns;
  m.can_interfaces = {"can0"};
  const double scale = 1.0 + sc.effects.magnitude(Effect::mass_error);
  const TruckParams& t = p_->truck;
  m.vehicle_text["name"] = sc.vehicle.name;
  m.vehicle_text["vin"] = t.vin;
  m.vehicle_text["description"] = t.description;
  m.vehicle_file = sc.vehicle;
  m.vehicle["mass_kg"] = t.total_mass_kg() * scale;
  for (const auto& a : t.axles) {
    m.vehicle[a.name + "_load_kg"] = a.load_kg * scale;
    m.vehicle[a.name + "_position_m"] = a.position_m;
    // Eq. 2.1's M_w. Not scaled by the mass-error effect: that is cargo, the axles weigh the same.
    m.vehicle[a.name + "_unsprung_kg"] = a.vertical.unsprung_kg;
  }
  m.vehicle["driven_before_s"] = sc.driven_before.count();
  m.vehicle["gnss_antenna_behind_front_axle_m"] = t.gnss_antenna_behind_front_m;
  m.vehicle["gnss_antenna_height_m"] = t.gnss_antenna_height_m;
  for (const auto& a : p_->accels) {
    recording::SensorInfo s;
    s.id = static_cast<std::int64_t>(&a - p_->accels.data());
    s.name = a.mount().name;
    s.kind = "accelerometer";
    s.position = a.mount().position;
    s.part = "MEMS, ADXL355-class, +-" + std::to_string(static_cast<int>(std::lround(a.mount().range_g))) + " g";
    s.rate_hz = a.rate_hz();
    m.sensors.push_back(s);
  }
  m.sensors.push_back({kGnssId, "GNSS", "gnss", "cab-rear-roof", "DGPS receiver", sc.gnss_rate_hz});
  m.sensors.push_back({kWeatherStationId, "WX", "weather", "roadside-mast", "weather station (5 s means)", 0.2});
  m.sensors.push_back({kWeatherStationId + 1, "ANEMO", "anemometer", "roadside-mast", "ultrasonic anemometer", 1.0});
  return m;
}

std::string Simulation::truth_toml() const {
  const Scenario& sc = p_->scenario;
  std::ostringstream o;
  o.precision(12);
  o << "# Ground truth of a simulated drive: never part of the recording.\n";
  o << "scenario = \"" << sc.name << "\"\n";
  o << "scenario_file = \"" << sc.source << "\"\n";
  o << "seed = " << p_->seed << "\n";
  o << "road_seed = " << sc.road_seed << "\n";
  o << "route = \"" << sc.route.name << "\"\n";
  o << "speed_mps = " << sc.speed_mps << "\n";
  o << "true_mass_kg = " << p_->truck.total_mass_kg() << "\n";
  o << "cda_m2 = " << p_->truck.cda_m2 << "\n";
  // Only when set, so the truth of a drive on the route's own tires reads as it always did.
  if (sc.tire_crr_scale != 1.0) {
    o << "tire_crr_scale = " << sc.tire_crr_scale << "  # cells.csv's crr: the route cell's (the pavement's own) times this\n";
  }
  o << "driveline_efficiency = " << p_->truck.driveline.efficiency << "\n";
  o << "effective_mass_at_end_kg = " << p_->plant.effective_mass_kg() << "  # in the gear driven at the end\n";
  // Where the fuel went over the run, in J: the truth of the estimator's fuel breakdown.
  const EnergyLedger& led = p_->plant.ledger();
  o << "\n[fuel_breakdown]\n";
  o << "fuel_l = " << led.fuel_j / (p_->truck.fuel.lhv_jpkg * p_->truck.fuel.density_kgpl) << "\n";
  o << "fuel_j = " << led.fuel_j << "\n";
  for (const BreakdownTruth& row : breakdown_truth(led)) o << row.name << "_j = " << row.energy_j << "\n";
  o << "\n[effects]\n";
  for (const auto& e : effect_catalog()) {
    if (sc.effects.on(e.id)) o << e.name << " = " << sc.effects.magnitude(e.id) << "\n";
  }
  return o.str();
}

std::vector<double> Simulation::accel_steps_mps2() const {
  std::vector<double> out;
  for (const auto& a : p_->accels) out.push_back(a.step_mps2());
  return out;
}

RunSummary Simulation::run(SampleSink& sink, TruthRecorder* truth, const std::function<void(double)>& progress) {
  Parts& p = *p_;
  const Scenario& sc = p.scenario;
  const double dt = 1.0 / sc.physics_rate_hz;
  RunSummary sum;
  p.plant.set_coasting(sc.coast);
  p.plant.start(sc.start_m, sc.speed_mps / p.speedometer, p.wind.at_truck());
  Kinematics before = p.kinematics(p.plant.state());
  double x_before = p.plant.state().x_m, v_before = p.plant.state().speed_mps;
  const double total = sc.end_m - sc.start_m;
  double next_progress = 0.01;
  auto emit_frame = [&](const CanFrame& f) {
    ++sum.frames;
    sink.frame(f);
  };
  const bool holding = !sc.hold_rpm.empty();
  for (;;) {
    p.wind.advance(dt);
    const Environment air = p.wind.at_truck();
    if (holding) {
      const auto step = static_cast<std::size_t>(p.plant.state().t_s / sc.hold.count());
      p.plant.set_hold_rpm(sc.hold_rpm[std::min(step, sc.hold_rpm.size() - 1)]);
    }
    if (sc.stops.every_m > 0) p.plant.set_cruise_speed(set_speed_mps(sc, p.plant.state().x_m) / p.speedometer);
    p.plant.step(dt, air);
    const TruckState& s = p.plant.state();
    const Kinematics now = p.kinematics(s);

    p.sample_accels(before, now, sink, sum);
    p.sample_gnss(before.t_s, dt, x_before, v_before, sink, sum);
    p.sample_weather(dt, sink, sum);
    p.update_vp1();
    if (p.bus.next_due_s() <= s.t_s) p.bus.run_until(s.t_s, p.view(s, air), emit_frame);
    if (truth != nullptr) truth->observe(s, air, dt);

    before = now;
    x_before = s.x_m;
    v_before = s.speed_mps;
    const double done = holding ? s.t_s / sc.duration->count() : (s.x_m - sc.start_m) / total;
    if (progress && done >= next_progress) {
      progress(std::min(done, 1.0));
      next_progress += 0.01;
    }
    const bool timed_out = sc.duration && s.t_s >= sc.duration->count();
    if (s.x_m >= sc.end_m || timed_out || (s.speed_mps <= 0.0 && !holding)) break;
  }
  sum.simulated_s = p.plant.state().t_s;
  sum.distance_m = p.plant.ledger().distance_m;
  sum.ledger = p.plant.ledger();
  return sum;
}

}  // namespace roadload::sim
