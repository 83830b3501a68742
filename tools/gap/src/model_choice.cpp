#include "roadload/gap/model_choice.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "roadload/definitions.hpp"
#include "roadload/recording/reader.hpp"
#include "roadload/vehicle_file.hpp"

namespace roadload::gap {
namespace {

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
    if (!chosen) return chosen.error();
    scenario = std::move(chosen.value());
  }
  if (truck) scenario->vehicle = *truck;
  auto run = read_run(recording, db, layout_for(scenario->route), scenario->vehicle);
  if (!run) return run.error();
  std::string label = std::filesystem::path(recording).filename().string();
  if (label.empty()) label = std::filesystem::path(recording).parent_path().filename().string();
  return RealRun{label, std::move(*scenario), std::move(run.value())};
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
