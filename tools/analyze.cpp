// roadload analyze: CRR per pavement cell from a recording (the force balance in an EKF, then a
// fixed-interval smoother), written as RESULTS/cells.csv and RESULTS/trip.json.
#include <cstdio>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "analyze_results.hpp"
#include "analyze_vibration.hpp"
#include "command.hpp"
#include "options.hpp"
#include "roadload/contact_forces.hpp"
#include "roadload/engine_loss_file.hpp"
#include "roadload/grade_file.hpp"
#include "roadload/drive_analyzer.hpp"
#include "roadload/recording/reader.hpp"
#include "roadload/recording/vehicle_setup.hpp"

namespace roadload::cli {
namespace {

constexpr const char* kHelp =
    "usage: roadload analyze <recording> --route ROUTE --out RESULTS [options]\n\n"
    "Estimates the coefficient of rolling resistance (CRR) along the drive and per pavement cell:\n"
    "the J1939 force balance (EEC1, EEC3, EC1, ETC2, CCVS1) in an EKF over speed, CRR, CdA, a\n"
    "torque bias and the speed's ripple from the road's roughness (the route's IRI per cell), with\n"
    "grade from the route's survey, air from the weather station, position from GNSS and odometry,\n"
    "then a fixed-interval smoother so each cell uses data on both sides of it.\n"
    "Per cell also: the fuel breakdown (engine, driveline, accessories, aero, rolling, grade,\n"
    "acceleration, braking; litres at 35.8 MJ/L) and, from the accelerometers, the contact force\n"
    "per axle (report Eq. 2.1) and the power the dampers and tires dissipate (dynamic rolling\n"
    "resistance, Eq. 2.7-2.8; the vehicle file's dampers and tire damping). Per pavement group\n"
    "(surface and panel length): PSDs, vibration modes and the concrete joint line.\n\n"
    "  --route R       route file or built-in route name (config/routes): geometry, grade, cells, IRI\n"
    "  --out DIR       write DIR/cells.csv (cell,crr,crr_lo,crr_hi,... 90 % interval; fuel breakdown per cell\n"
    "                  in litres; damper_power_w,tire_power_w,...), DIR/trip.json, and the PSDs:\n"
    "                  DIR/psd.csv (trip) and DIR/psd-<group>.csv (freq_hz, one column per accelerometer,\n"
    "                  (m/s^2)^2/Hz), DIR/psd-spatial-<group>.csv (cycles_per_m, per cycle/m)\n"
    "  --truth DIR     a simulation's ground truth: the true CRR beside each cell, RMSE and coverage, and\n"
    "                  the true fuel breakdown beside the estimate\n"
    "  --estimate-cda  fit CdA from the drive (drives across speeds); otherwise CdA keeps its prior\n"
    "  --cda M2 [--cda-sigma M2]  CdA's prior and its standard error (default: the vehicle file's, the\n"
    "                  type's value and spread); a measured value, for example `roadload calibrate --aero`\n"
    "  --cda-torque-correlation R  between that CdA's error and the flywheel torque's (-1..1; what\n"
    "                  `roadload calibrate --aero` prints: its CdA took up the engine-loss table's error)\n"
    "  --grade FILE    grade and its sigma from FILE (`roadload grade`) instead of the route's survey\n"
    "  --engine-losses FILE  the engine's friction + accessories by engine speed (`roadload calibrate`)\n"
    "                  instead of EEC3's whole percent; engine speeds outside it are not used\n"
    "  --survey-sigma M  the route survey's height error, carried into the force balance (default 0:\n"
    "                  the survey taken as exact)\n"
    "  --mass KG       vehicle mass (default: meta.toml vehicle.mass_kg, else the vehicle file's axle loads)\n"
    "  --dbc FILE      load FILE after the built-in definitions; repeatable\n"
    "  -q, --quiet     no table on standard output\n"
    "  -h, --help      this text\n";

}  // namespace

int run_analyze(Args args) {
  OptionParser opt("analyze", args);
  std::string recording, route_name, out, truth_dir, grade_file, losses_file;
  double survey_sigma = 0;
  std::optional<double> mass;
  std::vector<std::string> dbcs;
  bool quiet = false, estimate_cda = false;
  std::optional<double> cda_m2, cda_sigma_m2, cda_torque_correlation;
  while (opt.more()) {
    if (opt.flag("-h", "--help")) {
      std::fputs(kHelp, stdout);
      return kExitOk;
    }
    if (opt.flag("-q", "--quiet")) {
      quiet = true;
    } else if (opt.flag("--estimate-cda")) {
      estimate_cda = true;
    } else if (auto c = opt.real("--cda", 0.5, 30)) {
      cda_m2 = *c;
    } else if (auto cs = opt.real("--cda-sigma", 0.0001, 10)) {
      cda_sigma_m2 = *cs;
    } else if (auto cr = opt.real("--cda-torque-correlation", -1, 1)) {
      cda_torque_correlation = *cr;
    } else if (auto g = opt.value("--grade")) {
      grade_file = *g;
    } else if (auto l = opt.value("--engine-losses")) {
      losses_file = *l;
    } else if (auto sg = opt.real("--survey-sigma", 0, 10)) {
      survey_sigma = *sg;
    } else if (auto r = opt.value("--route")) {
      route_name = *r;
    } else if (auto o = opt.value("--out")) {
      out = *o;
    } else if (auto t = opt.value("--truth")) {
      truth_dir = *t;
    } else if (auto m = opt.real("--mass", 1000, 200000)) {
      mass = *m;
    } else if (auto d = opt.value("--dbc")) {
      dbcs.emplace_back(*d);
    } else if (auto p = opt.positional()) {
      recording = *p;
    } else if (!opt.failed()) {
      return opt.fail_unknown();
    }
  }
  if (opt.failed()) return kExitUsage;
  if (recording.empty()) return opt.fail("a recording is required");
  if (route_name.empty()) return opt.fail("--route is required");
  if (out.empty()) return opt.fail("--out is required");

  j1939::Database db;
  if (auto rc = load_definitions("analyze", dbcs, db)) return *rc;
  auto loaded = load_route("analyze", route_name);
  if (const int* rc = std::get_if<int>(&loaded)) return *rc;
  LoadedRoute& route = std::get<LoadedRoute>(loaded);
  auto reader = recording::RecordingReader::open(recording);
  if (!reader) {
    std::fprintf(stderr, "roadload analyze: %s\n", reader.error().to_string().c_str());
    return kExitNoInput;
  }
  auto vehicle = recording_vehicle("analyze", reader.value().metadata());
  if (const int* rc = std::get_if<int>(&vehicle)) return *rc;
  AnalyzerConfig cfg = recording::analyzer_config_for(std::get<Vehicle>(vehicle), reader.value().metadata(), mass);
  cfg.estimate_cda = estimate_cda;
  if (cda_m2) cfg.filter.truck.cda_prior_m2 = *cda_m2;
  if (cda_sigma_m2) cfg.filter.truck.cda_sigma_m2 = *cda_sigma_m2;
  if (cda_torque_correlation) cfg.filter.truck.cda_torque_bias_correlation = *cda_torque_correlation;
  cfg.survey_elevation_sigma_m = survey_sigma;
  cfg.roughness_iri_m_per_km = route.file.default_iri_m_per_km;
  if (!losses_file.empty()) {
    auto losses = load_engine_loss_file(losses_file);
    if (!losses) {
      std::fprintf(stderr, "roadload analyze: %s\n", losses.error().to_string().c_str());
      return losses.error().line > 0 ? kExitDataErr : kExitNoInput;
    }
    cfg.filter.truck.engine_losses = losses.value();
  }

  const std::vector<CellSpan> cells = cell_spans(route.file.cells);
  const double route_length_m = route.geometry.length_m();
  DriveAnalyzer analyzer(db, std::move(route.geometry), cells, cfg);
  if (!grade_file.empty()) {
    auto grade = load_grade_file(grade_file, route_length_m);
    if (!grade) {
      std::fprintf(stderr, "roadload analyze: %s\n", grade.error().to_string().c_str());
      return grade.error().line > 0 ? kExitDataErr : kExitNoInput;
    }
    analyzer.set_grade(std::move(grade.value()));
  }
  std::vector<std::string> axle_names;
  std::optional<ContactForces> contact;
  std::optional<VibrationAnalysis> vibration;
  const PavementGroups groups = pavement_groups(route.file.cells);
  auto layout = recording::axle_layout(reader.value().metadata(), std::get<Vehicle>(vehicle), recording + "/meta.toml");
  if (!layout.layout) {
    std::fprintf(stderr, "roadload analyze: contact forces and spectra not estimated: %s\n", layout.why_not.c_str());
  }
  for (const std::string& why : layout.skipped) std::fprintf(stderr, "roadload analyze: no contact force for %s\n", why.c_str());
  if (layout.layout) {
    for (const AxleContact& a : layout.layout->axles) axle_names.push_back(a.name);
    vibration.emplace(*layout.layout, recording::accelerometers(reader.value().metadata()), cells.size(), groups.cell_group,
                      groups.names.size());
    contact.emplace(std::move(*layout.layout), cells.size());
    analyzer.attach(&*contact);
    analyzer.attach(&*vibration);
  }
  while (const recording::Record* r = reader.value().next()) std::visit([&](const auto& s) { analyzer.push(s); }, *r);
  for (const auto& e : reader.value().errors().kept()) std::fprintf(stderr, "roadload analyze: %s\n", e.to_string().c_str());
  analyzer.finish();
  const std::vector<CellResult> results = analyzer.cells();
  const TripResult trip = analyzer.trip();

  std::optional<VibrationSummary> spectra;
  if (vibration) spectra = summarize(*vibration, groups, trip.fuel.time_s, trip.fuel.distance_m);
  std::error_code ec;
  std::filesystem::create_directories(out, ec);
  const VibrationAnalysis* va = vibration ? &*vibration : nullptr;
  for (auto err : {results::write_cells_csv(out + "/cells.csv", results, axle_names, va),
                   results::write_trip_json(out + "/trip.json", trip, spectra ? vibration_json(*spectra) : std::string()),
                   va ? write_psd_files(out, *va, groups) : std::nullopt}) {
    if (err) {
      std::fprintf(stderr, "roadload analyze: %s\n", err->to_string().c_str());
      return kExitCantCreate;
    }
  }
  std::optional<Truth> truth;
  if (!truth_dir.empty()) {
    auto t = read_truth(truth_dir);
    if (!t) {
      std::fprintf(stderr, "roadload analyze: %s\n", t.error().to_string().c_str());
      return t.error().line > 0 ? kExitDataErr : kExitNoInput;
    }
    truth = std::move(t.value());
  }
  if (!quiet) print_cells(results, truth ? &*truth : nullptr);
  print_trip(trip, results, truth ? &*truth : nullptr, va);
  if (spectra) print_vibration(*spectra);
  if (spectra && truth) print_vibration_truth(*vibration, route.file.cells, *truth);
  return kExitOk;
}

}  // namespace roadload::cli
