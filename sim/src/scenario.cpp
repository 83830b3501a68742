#include "roadload/sim/scenario.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <utility>

#include "roadload/sim/units.hpp"
#include "roadload/toml_fields.hpp"
#include "roadload/vehicle_file.hpp"

namespace roadload::sim {
namespace {

namespace fs = std::filesystem;

std::int64_t utc_ns(const toml::date_time& dt) {
  using namespace std::chrono;
  const sys_days day = year_month_day{year{dt.date.year}, month{dt.date.month}, std::chrono::day{dt.date.day}};
  const auto secs = sys_seconds{day}.time_since_epoch().count() + dt.time.hour * 3600 + dt.time.minute * 60 + dt.time.second;
  const std::int64_t offset = dt.offset ? std::int64_t{dt.offset->minutes} * 60 : 0;
  return (secs - offset) * 1'000'000'000LL + dt.time.nanosecond;
}

std::string resolve_route(const std::string& name, const fs::path& scenario_path) {
  const fs::path direct(name);
  if (direct.has_extension()) return direct.is_absolute() ? name : (scenario_path.parent_path() / direct).string();
  return (scenario_path.parent_path().parent_path() / "routes" / (name + ".toml")).string();
}

void read_weather(const detail::TomlFields& f, const toml::table& root, WeatherSpec& w) {
  const toml::table* t = root["weather"].as_table();
  if (t == nullptr) return;
  f.only(*t, {"air_temp_c", "pressure_pa", "wind_speed_mps", "wind_from_deg", "wander_mps", "temp_drift_c_per_h"}, "weather.");
  w.air_temp_c = f.number(*t, "air_temp_c", "weather.", w.air_temp_c);
  w.pressure_pa = f.number(*t, "pressure_pa", "weather.", w.pressure_pa);
  w.wind_speed_mps = f.number(*t, "wind_speed_mps", "weather.", w.wind_speed_mps);
  w.wind_from_deg = f.number(*t, "wind_from_deg", "weather.", w.wind_from_deg);
  w.wander_mps = f.number(*t, "wander_mps", "weather.", w.wander_mps);
  w.temp_drift_c_per_h = f.number(*t, "temp_drift_c_per_h", "weather.", w.temp_drift_c_per_h);
  if (w.pressure_pa < 50000 || w.pressure_pa > 110000) f.fail(t->get("pressure_pa"), "weather.pressure_pa", "outside 50-110 kPa");
  if (w.wind_speed_mps < 0) f.fail(t->get("wind_speed_mps"), "weather.wind_speed_mps", "negative");
}

void read_clocks(const detail::TomlFields& f, const toml::table& root, ClockSpec& c) {
  const toml::table* t = root["clocks"].as_table();
  if (t == nullptr) return;
  f.only(*t,
         {"can_rx_latency_s", "can_rx_jitter_s", "ecu_drift_ppm", "accel_offset_s", "accel_drift_ppm", "gnss_latency_s",
          "weather_offset_s"},
         "clocks.");
  c.can_rx_latency = Seconds{f.number(*t, "can_rx_latency_s", "clocks.", c.can_rx_latency.count())};
  c.can_rx_jitter = Seconds{f.number(*t, "can_rx_jitter_s", "clocks.", c.can_rx_jitter.count())};
  c.ecu_drift_ppm = f.number(*t, "ecu_drift_ppm", "clocks.", c.ecu_drift_ppm);
  c.accel_offset = Seconds{f.number(*t, "accel_offset_s", "clocks.", c.accel_offset.count())};
  c.accel_drift_ppm = f.number(*t, "accel_drift_ppm", "clocks.", c.accel_drift_ppm);
  c.gnss_latency = Seconds{f.number(*t, "gnss_latency_s", "clocks.", c.gnss_latency.count())};
  c.weather_offset = Seconds{f.number(*t, "weather_offset_s", "clocks.", c.weather_offset.count())};
  for (const char* key : {"can_rx_latency_s", "can_rx_jitter_s", "ecu_drift_ppm", "gnss_latency_s"}) {
    if (f.number(*t, key, "clocks.", 0.0) < 0) f.fail(t->get(key), std::string("clocks.") + key, "negative");
  }
  for (const char* key : {"accel_offset_s", "weather_offset_s", "gnss_latency_s"}) {
    if (std::abs(f.number(*t, key, "clocks.", 0.0)) > 10) f.fail(t->get(key), std::string("clocks.") + key, "beyond +-10 s");
  }
}

void read_effects(const detail::TomlFields& f, const toml::table& root, EffectSet& effects) {
  const toml::table* t = root["effects"].as_table();
  if (t == nullptr) return;
  for (const auto& [key, node] : *t) {
    const std::string name(key.str());
    const auto e = find_effect(name);
    if (!e) f.fail(&node, "effects." + name, "unknown effect (roadload simulate --list-effects)");
    const auto v = node.value<double>();
    if (!v) f.fail(&node, "effects." + name, "expected a number");
    effects.set(*e, *v);
  }
}

// Standing in neutral, the engine held at each speed for `hold_s`: nothing reaches the flywheel, so
// the indicated torque the engine reports is its own losses (an engine-loss calibration).
void read_rev_hold(const detail::TomlFields& f, const toml::table& root, Scenario& s) {
  const toml::node* list = root.get("hold_rpm");
  const toml::array* rpms = list != nullptr ? list->as_array() : nullptr;
  if (rpms == nullptr || rpms->empty()) f.fail(list, "hold_rpm", "rev-hold needs a list of engine speeds in rpm");
  for (const toml::node& n : *rpms) {
    const auto rpm = n.value<double>();
    if (!rpm || *rpm < 500 || *rpm > 2500) f.fail(&n, "hold_rpm", "expected engine speeds between 500 and 2500 rpm");
    s.hold_rpm.push_back(*rpm);
  }
  s.hold = Seconds{f.required_number(root, "hold_s", "")};
  if (s.hold.count() < 5 || s.hold.count() > 600) f.fail(root.get("hold_s"), "hold_s", "outside 5-600 s");
  if (root.contains("speed_mph") || root.contains("speed_mps")) {
    f.fail(root.get(root.contains("speed_mph") ? "speed_mph" : "speed_mps"), "mode", "rev-hold stands still: no speed");
  }
  s.coast = true;
  s.duration = s.hold * static_cast<double>(s.hold_rpm.size());
}

// The scenario's truck: a vehicle file beside it (with an extension), a built-in one by name, or
// the default vehicle.
Vehicle read_vehicle(const detail::TomlFields& f, const toml::table& root, const fs::path& path, const std::string& data_dir) {
  const std::string name = f.text(root, "vehicle", "").value_or(kDefaultVehicle);
  const fs::path direct(name);
  const std::string file = direct.has_extension() ? (direct.is_absolute() ? name : (path.parent_path() / direct).string())
                                                  : resolve_vehicle(name, data_dir);
  auto v = load_vehicle_file(file);
  if (!v) throw detail::TomlFailure{v.error()};
  return std::move(v.value());
}

// Cruise at a set speed (the default), a neutral coast-down, or a standstill rev-hold.
void read_mode(const detail::TomlFields& f, const toml::table& root, Scenario& s) {
  const auto mode = f.text(root, "mode", "");
  if (mode && *mode != "cruise" && *mode != "coast" && *mode != "rev-hold") {
    f.fail(root.get("mode"), "mode", "expected \"cruise\", \"coast\" or \"rev-hold\"");
  }
  if (mode == "rev-hold") {
    read_rev_hold(f, root, s);
    return;
  }
  const char* speed_key = root.contains("speed_mph") ? "speed_mph" : "speed_mps";
  if (auto mph = f.number(root, "speed_mph", "")) {
    s.speed_mps = *mph * kMps_per_mph;
  } else {
    s.speed_mps = f.required_number(root, "speed_mps", "");
  }
  if (s.speed_mps <= 0 || s.speed_mps > 40) f.fail(root.get(speed_key), speed_key, "outside 0-40 m/s (0-89 mph)");
  s.coast = mode == "coast";
}

void read_stops(const detail::TomlFields& f, const toml::table& root, Scenario& s) {
  const toml::table* t = root["stop_and_go"].as_table();
  if (t == nullptr) return;
  f.only(*t, {"every_m", "crawl_mph", "crawl_m"}, "stop_and_go.");
  s.stops.every_m = f.required_number(*t, "every_m", "stop_and_go.");
  s.stops.crawl_mps = f.required_number(*t, "crawl_mph", "stop_and_go.") * kMps_per_mph;
  s.stops.crawl_m = f.required_number(*t, "crawl_m", "stop_and_go.");
  if (s.stops.every_m < 100) f.fail(t->get("every_m"), "stop_and_go.every_m", "below 100 m");
  if (s.stops.crawl_mps < 1.0 || s.stops.crawl_mps >= s.speed_mps) {
    f.fail(t->get("crawl_mph"), "stop_and_go.crawl_mph", "outside 2.3 mph (first gear at idle) to the set speed");
  }
  if (s.stops.crawl_m <= 0 || s.stops.crawl_m >= s.stops.every_m) {
    f.fail(t->get("crawl_m"), "stop_and_go.crawl_m", "outside 0 to every_m");
  }
}

// This truck against its vehicle file: cargo, engine friction, accessories, drag area and tires.
void read_truck_scales(const detail::TomlFields& f, const toml::table& root, Scenario& s) {
  for (auto [key, value] : {std::pair{"load_scale", &s.load_scale}, std::pair{"engine_friction_scale", &s.engine_friction_scale},
                            std::pair{"accessory_scale", &s.accessory_scale}, std::pair{"cda_scale", &s.cda_scale}}) {
    *value = f.number(root, key, "", *value);
    if (*value < 0.5 || *value > 1.5) f.fail(root.get(key), key, "outside 0.5-1.5");
  }
  // Wider than the others: truck tires of one size span the EU label's classes A to E, about 4 to
  // 8 kg/t, a factor of two.
  s.tire_crr_scale = f.number(root, "tire_crr_scale", "", s.tire_crr_scale);
  if (s.tire_crr_scale < 0.5 || s.tire_crr_scale > 2.0) f.fail(root.get("tire_crr_scale"), "tire_crr_scale", "outside 0.5-2.0");
  if (auto u = f.text(root, "unsprung", "")) {
    if (*u != "physical" && *u != "report") f.fail(root.get("unsprung"), "unsprung", "expected \"physical\" or \"report\"");
    s.unsprung = *u == "report" ? UnsprungDefinition::report : UnsprungDefinition::physical;
  }
}

// The sensors' rates and how many accelerometers, and the physics' step.
void read_rates(const detail::TomlFields& f, const toml::table& root, Scenario& s) {
  s.accel_rate_hz = f.number(root, "accel_rate_hz", "", s.accel_rate_hz);
  if (s.accel_rate_hz < 1 || s.accel_rate_hz > 4000) f.fail(root.get("accel_rate_hz"), "accel_rate_hz", "outside 1-4000 Hz");
  const double count = f.number(root, "accelerometers", "", 8.0);
  if (count < 0 || count > 32) f.fail(root.get("accelerometers"), "accelerometers", "outside 0-32");
  s.accelerometers = static_cast<std::size_t>(count);
  s.gnss_rate_hz = f.number(root, "gnss_rate_hz", "", s.gnss_rate_hz);
  if (s.gnss_rate_hz < 0.1 || s.gnss_rate_hz > 100) f.fail(root.get("gnss_rate_hz"), "gnss_rate_hz", "outside 0.1-100 Hz");
  s.physics_rate_hz = std::max(f.number(root, "physics_rate_hz", "", s.physics_rate_hz), 2.0 * s.accel_rate_hz);
  if (s.physics_rate_hz > 20000) f.fail(root.get("physics_rate_hz"), "physics_rate_hz", "above 20 kHz");
}

Scenario read(const detail::TomlFields& f, const toml::table& root, const fs::path& path, const std::string& data_dir) {
  Scenario s;
  s.source = path.string();
  f.only(root,
         {"name",
          "description",
          "route",
          "speed_mph",
          "speed_mps",
          "start_m",
          "end_m",
          "duration_s",
          "driven_before_s",
          "start_utc",
          "road_seed",
          "load_scale",
          "engine_friction_scale",
          "accessory_scale",
          "cda_scale",
          "tire_crr_scale",
          "accel_rate_hz",
          "accelerometers",
          "gnss_rate_hz",
          "physics_rate_hz",
          "unsprung",
          "mode",
          "hold_rpm",
          "hold_s",
          "weather",
          "clocks",
          "effects",
          "stop_and_go",
          "vehicle"},
         "");
  s.name = f.required_text(root, "name", "");
  s.description = f.text(root, "description", "").value_or("");
  const std::string route_name = f.required_text(root, "route", "");
  auto route = load_route(resolve_route(route_name, path));
  if (!route) throw detail::TomlFailure{route.error()};
  s.route = std::move(route.value());
  s.vehicle = read_vehicle(f, root, path, data_dir);
  read_mode(f, root, s);
  s.start_m = f.number(root, "start_m", "", 0.0);
  if (auto end = f.number(root, "end_m", "")) s.end_m = *end;
  if (s.hold_rpm.empty()) {
    if (auto d = f.number(root, "duration_s", "")) s.duration = Seconds{*d};
  }
  s.driven_before = Seconds{f.number(root, "driven_before_s", "", s.driven_before.count())};
  if (!(s.driven_before.count() >= 0 && s.driven_before <= kMaxDrivenBefore)) {
    f.fail(root.get("driven_before_s"), "driven_before_s", "outside 0-86400 s");
  }
  if (const toml::node* utc = root.get("start_utc")) {
    const auto* dt = utc->as_date_time();
    if (dt == nullptr) f.fail(utc, "start_utc", "expected a TOML date-time such as 2014-10-20T10:00:00Z");
    s.start_utc_ns = utc_ns(dt->get());
  }
  if (const toml::node* seed = root.get("road_seed")) {
    if (!seed->is_integer() || *seed->value<std::int64_t>() < 0) f.fail(seed, "road_seed", "expected a non-negative integer");
    s.road_seed = static_cast<std::uint64_t>(*seed->value<std::int64_t>());
  }
  read_truck_scales(f, root, s);
  if (!s.coast) read_stops(f, root, s);
  read_rates(f, root, s);
  read_weather(f, root, s.weather);
  read_clocks(f, root, s.clocks);
  read_effects(f, root, s.effects);
  return s;
}

}  // namespace

Parsed<Scenario> load_scenario(std::string_view name_or_path, const std::string& data_dir) {
  fs::path path(name_or_path);
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) path = fs::path(data_dir) / "scenarios" / (std::string(name_or_path) + ".toml");
  if (!fs::is_regular_file(path, ec)) {
    return ParseError{std::string(name_or_path), 0, "scenario",
                      "neither a file nor a built-in scenario (roadload simulate --list-scenarios)"};
  }
  auto parsed = detail::parse_toml_file(path.string());
  if (!parsed) return parsed.error();
  detail::TomlFields f(path.string());
  try {
    Scenario s = read(f, parsed.value(), path, data_dir);
    // Build the route once here so that a scenario that loads is one that runs.
    auto built = Route::build(s.route);
    if (!built) return built.error();
    if (s.end_m == 0) s.end_m = built.value().length_m();
    if (s.end_m <= s.start_m) return ParseError{path.string(), 0, "end_m", "must lie after start_m"};
    return s;
  } catch (const detail::TomlFailure& e) {
    return e.error;
  }
}

std::vector<std::string> builtin_scenarios(const std::string& data_dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(fs::path(data_dir) / "scenarios", ec)) {
    if (entry.path().extension() == ".toml") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace roadload::sim
