#include "roadload/gap/model_choice.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>
#include <variant>
#include <vector>

#include "roadload/definitions.hpp"
#include "roadload/recording/reader.hpp"
#include "roadload/track_route.hpp"
#include "roadload/vehicle_file.hpp"

namespace roadload::gap {
namespace {

constexpr const char* kTracedModel = "traced";

Parsed<sim::Scenario> nearest_builtin(const RunConditions& c, const std::string& recording) {
  if (!c.have_fix) return ParseError{recording, 0, recording::kGnssFile, "no GNSS fix: name the model with --model"};
  std::optional<sim::Scenario> best;
  double best_dv = std::numeric_limits<double>::infinity();
  for (const std::string& name : sim::builtin_scenarios(data_dir())) {
    auto s = sim::load_scenario(name, data_dir());
    if (!s || s.value().coast) continue;
    const auto geometry = RouteGeometry::build(s.value().route.points);
    if (!geometry) continue;
    const auto p = geometry->project(c.first_lat_deg, c.first_lon_deg);
    if (p.offset_m > 30.0 || p.s_m < -50.0 || p.s_m > geometry->length_m() + 50.0) continue;
    const double dv = std::abs(s.value().speed_mps - c.mean_speed_mps);
    if (dv < best_dv) {
      best_dv = dv;
      best = std::move(s.value());
    }
  }
  if (!best)
    return ParseError{recording, 0, recording::kGnssFile, "the drive lies on no built-in route: name the model with --model"};
  return *best;
}

// A road no built-in scenario drives: the model drives the road the recording's own GNSS traces
// (its heights from that one pass, as `roadload analyze` traces it without a route), in cells of
// one pavement at the route defaults' CRR and roughness, at the recording's speed and weather.
Parsed<sim::Scenario> traced_model(const std::string& recording, const Vehicle& truck) {
  auto reader = recording::RecordingReader::open(recording);
  if (!reader) return reader.error();
  std::vector<GnssFix> fixes;
  while (const recording::Record* r = reader.value().next()) {
    if (const auto* fix = std::get_if<GnssFix>(r)) fixes.push_back(*fix);
  }
  const std::optional<TrackRoute> track = route_from_track(fixes, truck.gnss_antenna_height_m);
  const std::optional<RouteGeometry> geometry = track ? RouteGeometry::build(track->points) : std::nullopt;
  if (!geometry) {
    return ParseError{recording, 0, recording::kGnssFile,
                      "the drive lies on no built-in route and its GNSS traces no road (" + std::to_string(fixes.size()) +
                          " fixes): name the model with --model"};
  }
  sim::Scenario s;
  s.name = kTracedModel;
  s.description = "the road the recording's own GNSS traces";
  s.source = recording;
  s.route.name = "traced from " + std::filesystem::path(recording).filename().string();
  s.route.source = "the recording's GNSS, one pass";
  s.route.points = track->points;
  for (const CellSpan& c : fixed_length_cells(geometry->length_m(), TrackRouteConfig{}.cell_length_m)) {
    s.route.cells.push_back({c.id, c.start_m, c.end_m, "bituminous", s.route.default_crr, s.route.default_gd_n0_m3, 0});
  }
  s.vehicle = truck;
  s.end_m = geometry->length_m();
  s.start_utc_ns = fixes.front().utc_ns;
  // The recording's sensors, as many and as fast: the simulator mounts them in the vehicle file's
  // order, again from the first when there are more sensors than mounts.
  s.accelerometers = 0;
  for (const recording::SensorInfo& info : reader.value().metadata().sensors) {
    if (info.kind != "accelerometer") continue;
    ++s.accelerometers;
    if (info.rate_hz > 0) s.accel_rate_hz = info.rate_hz;
  }
  s.physics_rate_hz = std::max(s.physics_rate_hz, 2.0 * s.accel_rate_hz);
  return s;
}

}  // namespace

Parsed<RealRun> load_real_run(const std::string& recording, const std::string& model, const j1939::Database& db,
                              const std::optional<Vehicle>& vehicle) {
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
    // A first pass with no bins finds where the drive started.
    const RunLayout probe{*RouteGeometry::build(std::vector<GeoPoint>{{45, -93, 0}, {45.001, -93, 0}}), {}};
    auto fallback = truck ? Parsed<Vehicle>(*truck) : load_vehicle_file(default_vehicle_path());
    if (!fallback) return fallback.error();
    auto first = read_run(recording, db, probe, fallback.value());
    if (!first) return first.error();
    auto chosen = nearest_builtin(first.value().features.conditions, recording);
    if (!chosen && first.value().features.conditions.have_fix) chosen = traced_model(recording, fallback.value());
    if (!chosen) return chosen.error();
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
  const auto mass = run.recorded.meta.vehicle.find("mass_kg");
  char line[512];
  std::snprintf(line, sizeof line,
                "run %s: model %s (route %s), %.0f s at %.2f m/s, %.1f C, %.0f Pa, wind %.1f m/s from %.0f deg, mass %.0f kg",
                run.label.c_str(), run.model.name.c_str(), run.model.route.name.c_str(), c.duration_s, c.mean_speed_mps, c.air_temp_c,
                c.pressure_pa, c.wind_speed_mps, c.wind_from_deg, mass != run.recorded.meta.vehicle.end() ? mass->second : 0.0);
  return line;
}

}  // namespace roadload::gap
