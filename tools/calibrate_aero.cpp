// roadload calibrate --aero: the truck's CdA from two recorded drives over the same route's cells at
// two speeds (estimator/aero_calibration.hpp), printed as the options `roadload analyze` takes.
#include <cstdio>
#include <optional>
#include <variant>
#include <vector>

#include "calibrate_aero.hpp"

#include "files.hpp"
#include "progress.hpp"
#include "roadload/aero_calibration.hpp"
#include "roadload/engine_loss_file.hpp"
#include "roadload/pavement_groups.hpp"
#include "roadload/recording/reader.hpp"
#include "roadload/recording/vehicle_setup.hpp"
#include "roadload/recording/writer.hpp"
#include "roadload/tire_crr.hpp"

namespace roadload::cli {
namespace {

// The recording's cells as `roadload analyze` estimates them with this configuration: with the
// truck's accelerometers, the tires' own CRR (tire_crr.hpp). The road's dissipation grows with
// speed; left in, it would be fitted as drag.
Parsed<std::vector<CellResult>> analyse(const std::string& path, const j1939::Database& db, const LoadedRoute& route,
                                        const std::vector<CellSpan>& cells, const AnalyzerConfig& cfg, const Vehicle& vehicle) {
  auto reader = recording::RecordingReader::open(path);
  if (!reader) return reader.error();
  DriveAnalyzer analyzer(db, route.geometry, cells, cfg);
  if (route.grade) analyzer.set_grade(*route.grade);
  std::optional<VibrationAnalysis> vibration;
  const recording::LayoutResult layout = recording::axle_layout(reader.value().metadata(), vehicle, path + "/meta.toml");
  if (layout.layout) {
    const PavementGroups groups = pavement_groups(route.file.cells);
    vibration.emplace(*layout.layout, recording::accelerometers(reader.value().metadata()), cells.size(), groups.cell_group,
                      groups.names.size());
    analyzer.attach(&*vibration);
  }
  while (const recording::Record* r = reader.value().next()) std::visit([&](const auto& s) { analyzer.push(s); }, *r);
  if (!reader.value().errors().kept().empty()) return reader.value().errors().kept().front();
  analyzer.finish();
  return vibration ? with_tire_crr(analyzer.cells(), *vibration) : analyzer.cells();
}

// One drive analysed the three ways the fit needs; an exit code when it cannot be.
std::variant<int, AeroDrive> aero_drive(const std::string& path, const AeroOptions& o, const j1939::Database& db,
                                        const LoadedRoute& route, const model::EngineLossMap& losses, CalibrationDrives& out) {
  auto meta = recording::RecordingReader::open(path);
  if (!meta) {
    std::fprintf(stderr, "roadload calibrate: %s\n", meta.error().to_string().c_str());
    return kExitNoInput;
  }
  auto described = recording_vehicle("calibrate", meta.value().metadata(), o.vehicle);
  if (const int* rc = std::get_if<int>(&described)) return *rc;
  const Vehicle& vehicle = std::get<RecordingVehicle>(described).vehicle;
  if (!std::get<RecordingVehicle>(described).assumed.empty()) {
    std::fprintf(stderr, "roadload calibrate: %s: %s\n", path.c_str(), std::get<RecordingVehicle>(described).assumed.c_str());
  }
  AnalyzerConfig cfg = recording::analyzer_config_for(vehicle, meta.value().metadata(), std::nullopt);
  cfg.filter.truck.engine_losses = losses;
  cfg.roughness_iri_m_per_km = route.file.default_iri_m_per_km;
  if (o.cda_prior_m2) cfg.filter.truck.cda_prior_m2 = *o.cda_prior_m2;
  if (o.cda_sigma_m2) cfg.filter.truck.cda_sigma_m2 = *o.cda_sigma_m2;
  if (o.scale_step > 0) cfg.filter.truck.torque_scale_sigma = o.scale_step;
  out.cda_prior_m2 = cfg.filter.truck.cda_prior_m2;
  out.cda_sigma_m2 = cfg.filter.truck.cda_sigma_m2;
  out.torque_sigma_nm = losses.sigma_nm();
  const std::vector<CellSpan> cells = cell_spans(route.file.cells);
  std::optional<ParseError> failed;
  AeroDrive d = analyse_for_aero(
      cfg,
      [&](const AnalyzerConfig& c) {
        auto r = analyse(path, db, route, cells, c, vehicle);
        if (r) return std::move(r.value());
        failed = r.error();
        return std::vector<CellResult>{};
      },
      o.runs);
  if (failed) {
    std::fprintf(stderr, "roadload calibrate: %s\n", failed->to_string().c_str());
    return exit_for(*failed);
  }
  return d;
}

}  // namespace

int write_fit_csv(const std::string& path, const char* header, std::string_view row) {
  auto out = recording::OutputFile::create(path);
  if (!out) {
    std::fprintf(stderr, "roadload calibrate: %s\n", out.error().to_string().c_str());
    return kExitCantCreate;
  }
  out.value().write(header);
  out.value().write(row);
  if (auto err = out.value().close()) {
    std::fprintf(stderr, "roadload calibrate: %s\n", err->to_string().c_str());
    return kExitCantCreate;
  }
  return kExitOk;
}

std::variant<int, CalibrationDrives> calibration_drives(const AeroOptions& o, const j1939::Database& db) {
  auto losses = load_engine_loss_file(o.engine_losses);
  if (!losses) {
    std::fprintf(stderr, "roadload calibrate: %s\n", losses.error().to_string().c_str());
    return exit_for(losses.error());
  }
  std::vector<LoadedRoute> routes;
  for (const std::string& r : o.routes) {
    auto loaded = load_route("calibrate", r);
    if (const int* rc = std::get_if<int>(&loaded)) return *rc;
    routes.push_back(std::move(std::get<LoadedRoute>(loaded)));
  }
  CalibrationDrives out;
  // Each drive is analysed three ways: a dozen drives take a while, and the user sees how long.
  Progress progress("calibrate --aero: drives analysed", false, 5.0);
  for (std::size_t k = 0; k < o.recordings.size(); ++k) {
    const LoadedRoute& route = routes[routes.size() == 1 ? 0 : k / 2];
    auto d = aero_drive(o.recordings[k], o, db, route, losses.value(), out);
    if (const int* rc = std::get_if<int>(&d)) return *rc;
    out.drives.push_back(std::move(std::get<AeroDrive>(d)));
    progress.update(static_cast<double>(k + 1) / static_cast<double>(o.recordings.size()));
  }
  progress.finish();
  return out;
}

int run_calibrate_aero(const AeroOptions& o, const j1939::Database& db) {
  auto analysed = calibration_drives(o, db);
  if (const int* rc = std::get_if<int>(&analysed)) return *rc;
  const std::vector<AeroDrive>& drives = std::get<CalibrationDrives>(analysed).drives;
  const double prior_m2 = std::get<CalibrationDrives>(analysed).cda_prior_m2;
  std::vector<AeroPair> pairs;
  for (std::size_t k = 0; k + 1 < drives.size(); k += 2) pairs.push_back({&drives[k], &drives[k + 1]});
  const AeroCalibration fit = fit_cda(pairs, prior_m2, std::get<CalibrationDrives>(analysed).torque_sigma_nm);
  if (fit.cells == 0) {
    std::fprintf(stderr,
                 "roadload calibrate: %s and %s: fewer than two cells estimated in both, or speeds too close to tell "
                 "drag from rolling resistance: nothing written\n",
                 o.recordings[0].c_str(), o.recordings[1].c_str());
    return kExitDataErr;
  }
  if (!o.out.empty()) {
    recording::LineBuilder line;
    line.num(fit.cda_m2, 4).sep().num(fit.sigma_m2, 4).sep().num(fit.statistical_m2, 4).sep().num(fit.torque_m2, 4).sep();
    line.num(static_cast<std::int64_t>(fit.cells)).sep().num(fit.chi2_per_dof, 3).sep().num(fit.residual_correlation, 3).sep();
    line.num(fit.torque_bias_correlation, 3).sep().num(fit.cda_per_torque_scale_m2, 3);
    const int rc = write_fit_csv(o.out,
                                 "cda_m2,cda_sigma_m2,statistical_m2,torque_m2,cells,chi2_per_dof,residual_correlation,"
                                 "cda_torque_correlation,cda_per_torque_scale_m2\n",
                                 line.finish());
    if (rc != kExitOk) return rc;
  }
  std::printf(
      "CdA %.3f +- %.3f m^2 (cells' scatter %.3f, flywheel torque %.3f) from %zu cells, chi2/dof %.2f, neighbours' "
      "correlation %.2f; prior %.2f\n",
      fit.cda_m2, fit.sigma_m2, fit.statistical_m2, fit.torque_m2, fit.cells, fit.chi2_per_dof, fit.residual_correlation, prior_m2);
  std::printf(
      "roadload analyze ... --engine-losses %s --cda %.4f --cda-sigma %.4f --cda-torque-correlation %.3f "
      "--cda-per-torque-scale %.3f\n",
      o.engine_losses.c_str(), fit.cda_m2, fit.sigma_m2, fit.torque_bias_correlation, fit.cda_per_torque_scale_m2);
  return kExitOk;
}

}  // namespace roadload::cli
