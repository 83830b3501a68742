// roadload analyze: CRR per pavement cell from a recording (the force balance in an EKF, then a
// fixed-interval smoother), written as RESULTS/cells.csv, pavements.csv and trip.json.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "analyze_options.hpp"
#include "analyze_provenance.hpp"
#include "analyze_results.hpp"
#include "analyze_vibration.hpp"
#include "files.hpp"
#include "gnss_tracks.hpp"
#include "progress.hpp"
#include "roadload/analysis/analyze.hpp"
#include "roadload/contact_forces.hpp"
#include "roadload/content_hash.hpp"
#include "roadload/drive_analyzer.hpp"
#include "roadload/engine_loss_file.hpp"
#include "roadload/grade_file.hpp"
#include "roadload/grade_profile.hpp"
#include "roadload/gravity_check.hpp"
#include "roadload/numbers.hpp"
#include "roadload/recording/reader.hpp"
#include "roadload/recording/vehicle_setup.hpp"
#include "roadload/results/json.hpp"
#include "roadload/route_file.hpp"
#include "roadload/torque_scale_consider.hpp"
#include "roadload/track_route.hpp"

namespace roadload::cli {
namespace {

// A file the analysis reads beside the recording; prints its error and gives the exit status.
template <typename T>
std::optional<int> failed_input(const Parsed<T>& p) {
  if (p) return std::nullopt;
  say("analyze", p.error().to_string());
  return exit_for(p.error());
}

// The analyzer's settings: the recording's vehicle, then what the options say of the truck.
std::variant<AnalyzerConfig, int> configure(const AnalyzeOptions& o, const Vehicle& vehicle, const recording::Metadata& meta,
                                            double default_iri_m_per_km) {
  AnalyzerConfig cfg = recording::analyzer_config_for(vehicle, meta, o.mass);
  cfg.estimate_cda = o.estimate_cda;
  if (o.cda_m2) cfg.filter.truck.cda_prior_m2 = *o.cda_m2;
  if (o.cda_sigma_m2) cfg.filter.truck.cda_sigma_m2 = *o.cda_sigma_m2;
  if (o.cda_torque_correlation) cfg.filter.truck.cda_torque_bias_correlation = *o.cda_torque_correlation;
  if (o.cda_per_torque_scale_m2) cfg.filter.truck.cda_per_torque_scale_m2 = *o.cda_per_torque_scale_m2;
  if (o.torque_scale_sigma) cfg.filter.truck.torque_scale_sigma = *o.torque_scale_sigma;
  if (o.torque_scale) {
    // A CdA measured at a scale of 0 (calibrate --aero) is the drag of the torque the ECU states.
    cfg.filter.torque_scale_held = *o.torque_scale;
    cfg.filter.truck.cda_prior_m2 += cfg.filter.truck.cda_per_torque_scale_m2 * *o.torque_scale;
  }
  cfg.survey_elevation_sigma_m = o.survey_sigma;
  cfg.roughness_iri_m_per_km = default_iri_m_per_km;
  if (!o.losses_file.empty()) {
    auto losses = load_engine_loss_file(o.losses_file);
    if (auto rc = failed_input(losses)) return *rc;
    cfg.filter.truck.engine_losses = losses.value();
  }
  return cfg;
}

// The accelerometers' part of the analysis, attached where the recording's layout allows.
struct Accelerometers {
  std::vector<std::string> axle_names;
  std::optional<ContactForces> contact;
  std::optional<VibrationAnalysis> vibration;
};

void attach(Accelerometers& acc, DriveAnalyzer& analyzer, const AnalyzeOptions& o, const Vehicle& vehicle,
            const recording::Metadata& meta, const PavementGroups& groups) {
  auto layout = recording::axle_layout(meta, vehicle, o.recordings.front() + "/meta.toml");
  if (!layout.layout) say("analyze", "contact forces and spectra not estimated: " + layout.why_not);
  for (const std::string& why : layout.skipped) say("analyze", "no contact force for " + why);
  if (!layout.layout) return;
  const std::size_t cells = analyzer.cell_spans().size();
  for (const AxleContact& a : layout.layout->axles) acc.axle_names.push_back(a.name);
  acc.vibration.emplace(*layout.layout, recording::accelerometers(meta), cells, groups.cell_group, groups.names.size());
  acc.contact.emplace(std::move(*layout.layout), cells);
  analyzer.attach(&*acc.contact);
  analyzer.attach(&*acc.vibration);
}

// RESULTS/cells.csv, trip.json and the PSD files.
// `sensor_warnings` go into trip.json beside the numbers they put in doubt.
int write_results(const AnalyzeOptions& o, const DriveAnalysis& a, const Accelerometers& acc, const PavementGroups& groups,
                  const std::optional<VibrationSummary>& spectra, const std::vector<std::string>& sensor_warnings,
                  const Provenance& provenance, const std::vector<results::CellPlace>& places) {
  std::error_code ec;
  std::filesystem::create_directories(o.out, ec);
  const VibrationAnalysis* va = acc.vibration ? &*acc.vibration : nullptr;
  std::string extra = results::provenance_json(provenance) + ",\n" + results::pavements_json(a.pavements);
  if (spectra) extra += ",\n" + vibration_json(*spectra);
  if (!sensor_warnings.empty()) {
    extra += ",\n  \"accelerometer_warnings\": [";
    for (std::size_t i = 0; i < sensor_warnings.size(); ++i) extra += (i ? ", " : "") + results::json_quote(sensor_warnings[i]);
    extra += "]";
  }
  for (auto err :
       {results::write_cells_csv(o.out + "/cells.csv", a.cells, acc.axle_names, va, places, &provenance),
        results::write_pavements_csv(o.out + "/pavements.csv", a.pavements),
        results::write_trip_json(o.out + "/trip.json", a.trip, extra), va ? write_psd_files(o.out, *va, groups) : std::nullopt}) {
    if (err) {
      say("analyze", err->to_string());
      return kExitCantCreate;
    }
  }
  return kExitOk;
}

// The road the drive is analysed on: the route given, or the one the drive's own GNSS traces.
struct Road {
  RouteGeometry geometry;
  std::vector<CellDef> cells;  // a route file's, with their pavements; none for a traced road
  std::vector<CellSpan> spans;
  std::optional<GradeProfile> grade;  // a traced road's, from the same fixes, or the route's own
  double default_iri_m_per_km = AnalyzerConfig{}.roughness_iri_m_per_km;
  std::string unplaced;  // why the drive has no road, when it has none
  RouteIdentity identity;
};

// Without a route the drive's own GNSS traces one, its grade from that one pass (so wide, honest
// intervals); without GNSS either, the drive has no road: nothing can place it or give its grade.
Road traced_road(const RecordedTrack& recorded, const Vehicle& vehicle) {
  Road road;
  const std::vector<GnssFix>& fixes = recorded.fixes;
  const std::optional<TrackRoute> track = route_from_track(fixes, vehicle.gnss_antenna_height_m);
  const std::optional<RouteGeometry> geometry = track ? RouteGeometry::build(track->points) : std::nullopt;
  if (!geometry) {
    road.geometry = *RouteGeometry::build(std::vector<GeoPoint>{{0, 0, kNaN}, {0.001, 0, kNaN}});
    road.unplaced = "no route was given and the recording's GNSS traces no road (" + std::to_string(fixes.size()) +
                    " fixes): the drive cannot be placed, nor its grade known";
    return road;
  }
  road.geometry = *geometry;
  std::string points;
  for (const GeoPoint& p : track->points) points += std::to_string(p.lat_deg) + "," + std::to_string(p.lon_deg) + ";";
  road.identity = {"traced from the drive's GNSS", content_hash(points)};
  road.spans = fixed_length_cells(road.geometry.length_m(), TrackRouteConfig{}.cell_length_m);
  GradeConfig one_pass;
  one_pass.min_passes = 1;
  one_pass.pass_slope_sigma = kGnssPassSlopeSigma;
  const GnssTrack tracks[] = {{fixes, vehicle.gnss_antenna_height_m}};
  road.grade = GradeProfile::from_gnss(road.geometry, tracks, one_pass);
  return road;
}

// The drive's GNSS track: gnss.csv's, else the truck's VP1. Errors in the recording are the main
// read's to report; here a track is only looked for.
RecordedTrack drive_track(const AnalyzeOptions& o, const Vehicle& vehicle, const j1939::Database& db) {
  RecordedTrack recorded;
  std::uint64_t malformed = 0;
  TrackOptions antenna;
  antenna.antenna_height_m = vehicle.gnss_antenna_height_m;
  antenna.print_errors = false;
  read_recorded_track("analyze", o.recordings, antenna, db, recorded, malformed);
  return recorded;
}

// The route given, read before the recording so that a bad one is named at once.
std::optional<std::variant<Road, int>> given_road(const AnalyzeOptions& o) {
  if (o.route.empty()) return std::nullopt;
  auto loaded = load_route("analyze", o.route);
  if (const int* rc = std::get_if<int>(&loaded)) return *rc;
  LoadedRoute& route = std::get<LoadedRoute>(loaded);
  Road road;
  road.identity = {route.file.name, route_hash(route.file)};  // before its cells move
  road.geometry = std::move(route.geometry);
  road.spans = cell_spans(route.file.cells);
  road.cells = std::move(route.file.cells);
  road.default_iri_m_per_km = route.file.default_iri_m_per_km;
  road.grade = std::move(route.grade);
  return road;
}

// Each cell's surface and ends on the map, for cells.csv.
std::vector<results::CellPlace> places_of(const Road& road) {
  std::vector<std::string> surfaces;
  for (const CellDef& c : road.cells) surfaces.push_back(c.surface);
  return results::cell_places(road.geometry, road.spans, surfaces);
}

// The recording through the analyzer in capture-time order. A logger without a receiver of its
// own: the truck's VP1 places the drive, merged in time order. A run past a few seconds tells how
// far along the drive's fixes it is.
void drive(DriveAnalyzer& analyzer, recording::RecordingReader& reader, const RecordedTrack& track, const char* what, bool progress,
           GravityCheck* gravity = nullptr) {
  constexpr std::uint64_t kEvery = 1 << 16;  // records between looks at the clock
  const bool from_bus = track.source.rfind("J1939", 0) == 0;
  const double span_s = track.fixes.empty() ? 0.0 : to_seconds(track.fixes.back().t - track.fixes.front().t);
  Progress told(what, !progress || span_s <= 0, 5.0);
  std::size_t bus_fix = 0;
  std::uint64_t n = 0;
  while (const recording::Record* r = reader.next()) {
    const CaptureTime t = std::visit([](const auto& s) { return s.t; }, *r);
    if (++n % kEvery == 0 && span_s > 0) told.update(std::clamp(to_seconds(t - track.fixes.front().t) / span_s, 0.0, 1.0));
    while (from_bus && bus_fix < track.fixes.size() && track.fixes[bus_fix].t <= t) analyzer.push(track.fixes[bus_fix++]);
    if (const auto* a = std::get_if<AccelSample>(r); a != nullptr && gravity != nullptr) gravity->push(*a);
    std::visit([&](const auto& s) { analyzer.push(s); }, *r);
  }
  told.finish();
}

// A sensor whose z lacks gravity is named with what that means, on standard error and in trip.json;
// its numbers are not dropped.
std::vector<std::string> tell_gravity(const GravityCheck& gravity, const recording::Metadata& meta) {
  std::vector<std::string> out;
  for (const GravityCheck::Finding& f : gravity.implausible()) {
    std::string name = "sensor " + std::to_string(f.sensor);
    for (const recording::SensorInfo& s : meta.sensors) {
      if (s.id == f.sensor) name = s.name + (s.position.empty() ? "" : " (" + s.position + ")");
    }
    char text[512];
    std::snprintf(text, sizeof text,
                  "accelerometer %s: mean z %.2f m/s^2 over %llu samples, where the format's z includes gravity, up as "
                  "mounted (+9.81): mounted upside down or on its side, or gravity taken out; its contact forces and dynamic "
                  "power are suspect",
                  name.c_str(), f.mean_z_mps2, static_cast<unsigned long long>(f.samples));
    say("analyze", text);
    out.emplace_back(text);
  }
  return out;
}

// The command's tables: the cells on standard output, the trip, the pavements and the spectra on
// standard error, each beside a simulation's truth when given.
void tell(const AnalyzeOptions& o, const DriveAnalysis& analysis, const Accelerometers& acc,
          const std::optional<VibrationSummary>& spectra, const std::vector<CellDef>& cells, const Truth* truth) {
  const VibrationAnalysis* va = acc.vibration ? &*acc.vibration : nullptr;
  if (!o.quiet) print_cells(analysis.cells, truth);
  print_trip(analysis.trip, analysis.cells, truth, va);
  print_pavements(analysis.pavements);
  if (spectra) print_vibration(*spectra);
  if (spectra && truth) print_vibration_truth(*acc.vibration, cells, *truth);
}

int analyze(const AnalyzeOptions& o) {
  j1939::Database db;
  if (auto rc = load_definitions("analyze", o.dbcs, db)) return *rc;
  auto found = given_road(o);
  if (found && std::holds_alternative<int>(*found)) return std::get<int>(*found);
  auto reader = recording::RecordingReader::open_drive(o.recordings);
  if (!reader) {
    say("analyze", reader.error().to_string());
    return exit_for(reader.error());
  }
  const recording::Metadata& meta = reader.value().metadata();
  auto described = recording_vehicle("analyze", meta, o.vehicle);
  if (const int* rc = std::get_if<int>(&described)) return *rc;
  const Vehicle& vehicle = std::get<RecordingVehicle>(described).vehicle;
  const std::string& assumed = std::get<RecordingVehicle>(described).assumed;
  if (!assumed.empty()) say("analyze", assumed);
  const RecordedTrack track = drive_track(o, vehicle, db);
  if (!found) found = traced_road(track, vehicle);
  Road& road = std::get<Road>(*found);
  auto cfg = configure(o, vehicle, meta, road.default_iri_m_per_km);
  if (const int* rc = std::get_if<int>(&cfg)) return *rc;
  std::optional<GradeProfile> grade = std::move(road.grade);
  if (!o.grade_file.empty()) {
    auto file = load_grade_file(o.grade_file, road.geometry.length_m());
    if (auto rc = failed_input(file)) return *rc;
    grade = std::move(file.value());
  }
  const PavementGroups groups = pavement_groups(road.cells);
  Accelerometers acc;
  GravityCheck gravity;
  // The torque scale's second run reads the force balance's streams again; its parse errors are the
  // first run's and are not told twice.
  bool reread = true;
  auto run = [&](const AnalyzerConfig& c, TorqueScaleRun which) {
    DriveAnalyzer analyzer(db, road.geometry, road.spans, c);
    if (grade) analyzer.set_grade(*grade);
    if (which == TorqueScaleRun::held) {
      attach(acc, analyzer, o, vehicle, meta, groups);
      drive(analyzer, reader.value(), track, "analyze", o.progress, &gravity);
    } else if (auto again = recording::RecordingReader::open_drive(
                   o.recordings, recording::kCanStream | recording::kGnssStream | recording::kWeatherStream)) {
      drive(analyzer, again.value(), track, "analyze (the torque scale's second run)", o.progress);
    } else {
      say("analyze", "reading it again: " + again.error().to_string());
      reread = false;
    }
    analyzer.finish(groups);
    return DriveAnalysis{analyzer.cells(), analyzer.trip(), analyzer.pavements()};
  };
  DriveAnalysis analysis = analyse_with_torque_scale(std::get<AnalyzerConfig>(cfg), run);
  if (!reread) return kExitNoInput;
  for (const auto& e : reader.value().errors().kept()) say("analyze", e.to_string());
  const std::vector<std::string> sensor_warnings = tell_gravity(gravity, meta);
  std::vector<CellResult>& results = analysis.cells;
  TripResult& trip = analysis.trip;
  for (const std::string* why : {static_cast<const std::string*>(&road.unplaced), &assumed}) {
    if (why->empty()) continue;
    withhold(trip, results, *why);
    for (PavementResult& p : analysis.pavements) withhold(p.crr, *why);
  }
  std::optional<VibrationSummary> spectra;
  if (acc.vibration) spectra = summarize(*acc.vibration, groups, trip.fuel.time_s, trip.fuel.distance_m);
  const Provenance origin = provenance(o, meta, vehicle, assumed, track, std::get<AnalyzerConfig>(cfg), road.identity);
  if (const int rc = write_results(o, analysis, acc, groups, spectra, sensor_warnings, origin, places_of(road)); rc != kExitOk)
    return rc;
  std::optional<Truth> truth;
  if (!o.truth_dir.empty()) {
    auto t = read_truth(o.truth_dir);
    if (auto rc = failed_input(t)) return *rc;
    truth = std::move(t.value());
  }
  if (o.report) tell(o, analysis, acc, spectra, road.cells, truth ? &*truth : nullptr);
  return reader.value().errors().count() > 0 ? kExitDataErr : kExitOk;
}

}  // namespace
}  // namespace roadload::cli

namespace roadload::analysis {

int analyze(AnalyzeOptions o) {
  return cli::on_one_drive("analyze", o.recordings, [&] { return cli::analyze(o); });
}

}  // namespace roadload::analysis
