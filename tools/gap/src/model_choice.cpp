#include "roadload/gap/model_choice.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "roadload/definitions.hpp"
#include "roadload/recording/reader.hpp"
#include "roadload/track_route.hpp"
#include "roadload/vehicle_file.hpp"

namespace roadload::gap {
namespace {

constexpr const char* kTracedModel = "traced";

// A neutral coast-down: the driveline disengaged for most of the run. Its model is a coast, not
// the cruise nearest its mean speed, which would fit the truck's mass to the deceleration.
bool coasting(const RunConditions& c) { return c.speed_samples > 0 && c.disengaged_share >= 0.8; }

// A cruise model turned into the coast-down the recording holds, from its entry speed.
void as_coast(sim::Scenario& s, const RunConditions& c) {
  if (s.coast) return;
  s.coast = true;
  s.stops = {};
  if (c.first_speed_mps > 0.5) s.speed_mps = c.first_speed_mps;
  char why[160];
  std::snprintf(why, sizeof why, "; a neutral coast-down from %.1f m/s (the driveline disengaged %.0f %% of the run)", s.speed_mps,
                100.0 * c.disengaged_share);
  s.description += why;
}

// The built-in scenario whose route the first fix lies on: for a cruise the one whose set speed is
// nearest the drive's mean; for a coast-down a coast scenario of that route with the nearest entry
// speed, else that route's cruise nearest the entry speed (load_real_run turns it into a coast).
Parsed<sim::Scenario> nearest_builtin(const RunConditions& c, const std::string& recording) {
  if (!c.have_fix) return ParseError{recording, 0, recording::kGnssFile, "no GNSS fix: name the model with --model"};
  const bool coast = coasting(c);
  std::optional<sim::Scenario> best;
  double best_score = std::numeric_limits<double>::infinity();
  for (const std::string& name : sim::builtin_scenarios(data_dir())) {
    auto s = sim::load_scenario(name, data_dir());
    if (!s || (s.value().coast && !coast)) continue;
    const auto geometry = RouteGeometry::build(s.value().route.points);
    if (!geometry) continue;
    const auto p = geometry->project(c.first_lat_deg, c.first_lon_deg);
    if (p.offset_m > 30.0 || p.s_m < -50.0 || p.s_m > geometry->length_m() + 50.0) continue;
    const double dv = std::abs(s.value().speed_mps - (coast ? c.first_speed_mps : c.mean_speed_mps));
    // A coast scenario before any cruise for a coast-down: it starts where the road allows one.
    const double score = dv + (coast && !s.value().coast ? 1000.0 : 0.0);
    if (score < best_score) {
      best_score = score;
      best = std::move(s.value());
    }
  }
  if (!best)
    return ParseError{recording, 0, recording::kGnssFile, "the drive lies on no built-in route: name the model with --model"};
  return *best;
}

// What the model of a drive on a road of its own needs from the recording: its fixes and sensors.
struct DriveFacts {
  std::vector<GnssFix> fixes;
  recording::Metadata meta;
};
Parsed<DriveFacts> read_facts(const std::string& recording) {
  auto reader = recording::RecordingReader::open(recording);
  if (!reader) return reader.error();
  DriveFacts f;
  while (const recording::Record* r = reader.value().next()) {
    if (const auto* fix = std::get_if<GnssFix>(r)) f.fixes.push_back(*fix);
  }
  f.meta = reader.value().metadata();
  return f;
}

// A cruise of the truck along `route` from where the drive's first fix lies, with the recording's
// accelerometers, as many and as fast: the simulator mounts them in the vehicle file's order,
// again from the first when there are more sensors than mounts.
Parsed<sim::Scenario> cruise(sim::RouteDef route, const DriveFacts& f, const Vehicle& truck, const std::string& recording) {
  const std::optional<RouteGeometry> geometry = RouteGeometry::build(route.points);
  if (!geometry || f.fixes.empty()) {
    return ParseError{recording, 0, recording::kGnssFile, "no GNSS fix to place the drive on route " + route.name};
  }
  const auto start = geometry->project(f.fixes.front().lat_deg, f.fixes.front().lon_deg);
  if (start.offset_m > 50.0) {
    return ParseError{
        recording, 0, recording::kGnssFile,
        "the drive's first fix lies " + std::to_string(static_cast<int>(start.offset_m)) + " m off route " + route.name};
  }
  // The first fix's epoch becomes the model's time zero, and a scenario starts with its front
  // axle: the antenna is that far behind it. Metres matter: a model shifted along the road meets
  // every bump of its profile early or late, which the vibration features see. One fix is a
  // metre off, so the start is the mean over the first ten seconds' fixes, each taken back by
  // the distance driven since the first (its speed integrated).
  double travelled_m = 0, sum_m = 0;
  std::size_t used = 0;
  for (std::size_t i = 0; i < f.fixes.size() && i < 100; ++i) {
    if (i > 0) {
      const double dt_s = to_seconds(f.fixes[i].t - f.fixes[i - 1].t);
      travelled_m += 0.5 * (f.fixes[i].speed_mps + f.fixes[i - 1].speed_mps) * dt_s;
    }
    const auto p = geometry->project(f.fixes[i].lat_deg, f.fixes[i].lon_deg);
    if (p.offset_m > 50.0) continue;
    sum_m += p.s_m - travelled_m;
    ++used;
  }
  const double start_m = sum_m / static_cast<double>(std::max<std::size_t>(1, used)) + truck.gnss_antenna_behind_front_m;
  sim::Scenario s;
  s.name = route.name;
  s.description = "a cruise on route " + route.name + " at the recording's speed";
  s.source = route.source_file.empty() ? recording : route.source_file;
  s.route = std::move(route);
  s.vehicle = truck;
  s.start_m = std::max(0.0, start_m);
  s.end_m = geometry->length_m();
  s.start_utc_ns = f.fixes.front().utc_ns;
  s.accelerometers = 0;
  for (const recording::SensorInfo& info : f.meta.sensors) {
    if (info.kind != "accelerometer") continue;
    ++s.accelerometers;
    if (info.rate_hz > 0) s.accel_rate_hz = info.rate_hz;
  }
  s.physics_rate_hz = std::max(s.physics_rate_hz, 2.0 * s.accel_rate_hz);
  return s;
}

// A road no built-in scenario drives and no route file describes: the model drives the road the
// recording's own GNSS traces (its heights from that one pass, as `roadload analyze` traces it
// without a route), in cells of one pavement at the route defaults' CRR and roughness.
Parsed<sim::Scenario> traced_model(const std::string& recording, const Vehicle& truck) {
  auto facts = read_facts(recording);
  if (!facts) return facts.error();
  const std::vector<GnssFix>& fixes = facts.value().fixes;
  const std::optional<TrackRoute> track = route_from_track(fixes, truck.gnss_antenna_height_m);
  const std::optional<RouteGeometry> geometry = track ? RouteGeometry::build(track->points) : std::nullopt;
  if (!geometry) {
    return ParseError{recording, 0, recording::kGnssFile,
                      "the drive lies on no built-in route and its GNSS traces no road (" + std::to_string(fixes.size()) +
                          " fixes): name the model with --model or its road with --route"};
  }
  sim::RouteDef route;
  route.name = "traced from " + std::filesystem::path(recording).filename().string();
  route.source = "the recording's GNSS, one pass";
  route.points = track->points;
  for (const CellSpan& c : fixed_length_cells(geometry->length_m(), TrackRouteConfig{}.cell_length_m)) {
    route.cells.push_back({c.id, c.start_m, c.end_m, "bituminous", route.default_crr, route.default_gd_n0_m3, 0});
  }
  auto s = cruise(std::move(route), facts.value(), truck, recording);
  if (s) {
    s.value().name = kTracedModel;
    s.value().description = "the road the recording's own GNSS traces";
  }
  return s;
}

// The model on a route the user gives (a route file: their own GNSS or GIS sections).
Parsed<sim::Scenario> route_model(const std::string& recording, const std::string& route_path, const Vehicle& truck) {
  auto route = sim::load_route(route_path);
  if (!route) return route.error();
  auto facts = read_facts(recording);
  if (!facts) return facts.error();
  return cruise(std::move(route.value()), facts.value(), truck, recording);
}

}  // namespace

Parsed<RealRun> load_real_run(const std::string& recording, const std::string& model, const j1939::Database& db,
                              const std::optional<Vehicle>& vehicle, const std::string& route) {
  std::optional<Vehicle> truck = vehicle;
  if (!truck) {
    auto opened = recording::RecordingReader::open(recording);
    if (!opened) return opened.error();
    truck = opened.value().metadata().vehicle_file;
  }
  // The layout needs the route, the route may need the recording: read the model first when named.
  std::optional<sim::Scenario> scenario;
  if (!model.empty()) {
    auto s = sim::load_scenario(model, data_dir());
    if (!s) return s.error();
    scenario = std::move(s.value());
  }
  if (!scenario) {
    // A first pass with no bins finds where the drive started and whether it coasted.
    const RunLayout probe{*RouteGeometry::build(std::vector<GeoPoint>{{45, -93, 0}, {45.001, -93, 0}}), {}};
    auto fallback = truck ? Parsed<Vehicle>(*truck) : load_vehicle_file(default_vehicle_path());
    if (!fallback) return fallback.error();
    auto first = read_run(recording, db, probe, fallback.value());
    if (!first) return first.error();
    const RunConditions& c = first.value().features.conditions;
    auto chosen = route.empty() ? nearest_builtin(c, recording) : route_model(recording, route, fallback.value());
    if (!chosen && route.empty() && c.have_fix) chosen = traced_model(recording, fallback.value());
    if (!chosen) return chosen.error();
    if (coasting(c)) as_coast(chosen.value(), c);
    scenario = std::move(chosen.value());
  }
  if (truck) scenario->vehicle = *truck;
  auto run = read_run(recording, db, layout_for(scenario->route), scenario->vehicle);
  if (!run) return run.error();
  std::string label = std::filesystem::path(recording).filename().string();
  if (label.empty()) label = std::filesystem::path(recording).parent_path().filename().string();
  RealRun out{label, std::move(*scenario), std::move(run.value()), {}};
  if (out.model.name == kTracedModel) {
    out.caveat =
        "the model's road is traced from this drive's own GNSS: one pass's heights, no pavement or roughness; that "
        "error is not in the noise floor, so no effect is named (give a surveyed route's scenario with --model)";
  }
  return out;
}

std::string describe(const RealRun& run) {
  const RunConditions& c = run.recorded.features.conditions;
  const auto& vehicle = run.recorded.meta.vehicle;
  const auto mass = vehicle.find("mass_kg");
  char line[512];
  std::snprintf(line, sizeof line,
                "run %s: model %s (route %s%s), %.0f s at %.2f m/s, %.1f C, %.0f Pa, wind %.1f m/s from %.0f deg, mass %.0f kg",
                run.label.c_str(), run.model.name.c_str(), run.model.route.name.c_str(), run.model.coast ? ", coast-down" : "",
                c.duration_s, c.mean_speed_mps, c.air_temp_c, c.pressure_pa, c.wind_speed_mps, c.wind_from_deg,
                mass != vehicle.end() ? mass->second : 0.0);
  return std::string(line) + ", driven " + std::to_string(std::lround(driven_before(run.recorded.meta, run.model).count() / 60.0)) +
         " min before";
}

}  // namespace roadload::gap
