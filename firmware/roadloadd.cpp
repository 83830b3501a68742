// roadloadd: the daemon's process. Everything it does is in the firmware library; this file reads
// the command line, builds the sources, and turns signals and the status interval into calls.
#include <signal.h>
#include <systemd/sd-daemon.h>

#include <cstdio>
#include <optional>
#include <string>
#include <vector>

#include "roadload/accel/adxl355.hpp"
#include "roadload/content_hash.hpp"
#include "roadload/definitions.hpp"
#include "roadload/engine_loss_file.hpp"
#include "roadload/firmware/command_line.hpp"
#include "roadload/firmware/daemon.hpp"
#include "roadload/firmware/sources.hpp"
#include "roadload/firmware/status_log.hpp"
#include "roadload/io/directory_lock.hpp"
#include "roadload/io/posix_time.hpp"
#include "roadload/recording/flac_accel.hpp"
#include "roadload/recording/metadata_vehicle.hpp"
#include "roadload/recording/vehicle_setup.hpp"
#include "roadload/route_file.hpp"
#include "roadload/vehicle_file.hpp"

namespace {

using namespace roadload;
using namespace roadload::firmware;

int fail(const std::string& what) {
  std::fprintf(stderr, "roadloadd: %s\n", what.c_str());
  return 1;
}

struct Estimation {
  std::optional<Vehicle> vehicle;  // the configured one
  j1939::Database db;
  RouteGeometry route;
  std::vector<CellSpan> cells;
  std::vector<std::string> surfaces;
  double iri_m_per_km = AnalyzerConfig{}.roughness_iri_m_per_km;  // the route's, where a cell states none
  PavementGroups groups;
  model::EngineLossMap engine_losses;
  std::string route_name, route_hash;
};

std::optional<ParseError> load_estimation(const DaemonConfig& c, Estimation& e) {
  if (!c.vehicle.file.empty()) {
    auto vehicle = load_vehicle_file(resolve_vehicle(c.vehicle.file));
    if (!vehicle) return vehicle.error();
    e.vehicle = std::move(vehicle.value());
  }
  if (auto err = load_dbc_file(e.db, core_dbc_path())) return err;
  if (c.estimator.route.empty()) return std::nullopt;
  auto route = load_route_file(resolve_route(c.estimator.route));
  if (!route) return route.error();
  auto geometry = RouteGeometry::build(route.value().points);
  if (!geometry) return ParseError{route.value().source_file, 0, "point", "the route's points do not make a route"};
  e.route = std::move(*geometry);
  e.cells = cell_spans(route.value().cells);
  for (const CellDef& cell : route.value().cells) e.surfaces.push_back(cell.surface);
  e.iri_m_per_km = route.value().default_iri_m_per_km;
  e.groups = pavement_groups(route.value().cells);
  e.route_name = route.value().name;
  e.route_hash = route_hash(route.value());
  if (!c.estimator.engine_losses.empty()) {
    auto losses = load_engine_loss_file(c.estimator.engine_losses);
    if (!losses) return losses.error();
    e.engine_losses = losses.value();
  }
  return std::nullopt;
}

// The recording's meta.toml: a replay's with this daemon's clock and, when one is configured, its
// vehicle file; a truck's with its sensors and vehicle file.
recording::Metadata metadata(const DaemonConfig& c, const BuiltSources& b, const std::optional<Vehicle>& vehicle) {
  recording::Metadata m = b.replaying ? b.replayed : recording::Metadata{};
  if (vehicle) {
    m.vehicle_file = *vehicle;
    m.vehicle_text["name"] = vehicle->name;
    if (!vehicle->vin.empty()) m.vehicle_text["vin"] = vehicle->vin;
  }
  m.created_by = std::string("roadloadd ") + ROADLOAD_VERSION;
  m.clock_source = b.replaying ? "kernel (CAN), replayed (sensors)" : "kernel";
  m.can_interfaces = b.interfaces;
  if (!b.replaying) {
    for (const AccelConfig& a : c.accelerometers) {
      m.sensors.push_back({a.id, a.name, "accelerometer", a.position, "ADXL355", a.odr_hz});
    }
  }
  return m;
}

// What the live results are made of; the daemon adds the run's id and the drive's UTC span.
results::Provenance provenance(const DaemonConfig& c, const Vehicle& vehicle, const Estimation& est, const model::TruckModel& truck) {
  results::Provenance p;
  p.program = std::string("roadloadd ") + ROADLOAD_VERSION;
  p.vehicle = vehicle.name;
  p.vin = vehicle.vin;
  p.vehicle_source = c.vehicle.file.empty() ? "the replayed recording's meta.toml" : "[vehicle] file " + c.vehicle.file;
  p.vehicle_hash = content_hash(format_vehicle(vehicle));
  p.route = c.estimator.route;
  p.route_name = est.route_name;
  p.route_hash = est.route_hash;
  p.engine_losses = results::engine_losses_text(c.estimator.engine_losses);
  p.cda = results::cda_text(truck.cda_prior_m2, truck.cda_sigma_m2,
                            c.estimator.cda_m2 > 0 ? "[estimator] cda_m2" : "the vehicle file");
  return p;
}

// The force balance needs the route's grade and the truck: without both the daemon records and
// reports only. A replay's recording states its drive (cargo, antenna) over the vehicle file.
void configure_estimator(const DaemonConfig& c, const Estimation& est, DaemonSetup& setup, std::vector<std::string>& notes) {
  const std::optional<Vehicle>& described = setup.metadata.vehicle_file;
  if (c.estimator.route.empty()) notes.push_back("estimator: no route configured, CRR not estimated");
  if (!described) notes.push_back("estimator: no vehicle file ([vehicle] file), CRR not estimated");
  if (c.estimator.route.empty() || !described) return;
  setup.db = &est.db;
  setup.route = est.route;
  setup.cells = est.cells;
  setup.surfaces = est.surfaces;
  const Vehicle vehicle = recording::vehicle_from_metadata(*described, setup.metadata);
  setup.analyzer = recording::analyzer_config_for(vehicle, setup.metadata, std::nullopt);
  setup.analyzer.roughness_iri_m_per_km = est.iri_m_per_km;
  model::TruckModel& truck = setup.analyzer.filter.truck;
  truck.engine_losses = est.engine_losses;
  if (c.estimator.cda_m2 > 0) truck.cda_prior_m2 = c.estimator.cda_m2;
  if (c.estimator.cda_sigma_m2 > 0) truck.cda_sigma_m2 = c.estimator.cda_sigma_m2;
  truck.cda_torque_bias_correlation = c.estimator.cda_torque_correlation;
  // The live filter runs forward only: the torque, efficiency and mass scales' Schmidt gains let
  // its CRR swing on replay timing (docs/roadloadd.md, "Not done yet"); the recording's analysis
  // carries them.
  truck.torque_scale_sigma = 0;
  truck.efficiency_scale_sigma = 0;
  truck.mass_sigma_kg = 0;
  setup.provenance = provenance(c, vehicle, est, truck);
  recording::LayoutResult layout = recording::axle_layout(setup.metadata, vehicle, "accelerometers");
  if (layout.layout) {
    setup.layout = std::move(layout.layout);
    setup.accelerometers = recording::accelerometers(setup.metadata);
    setup.cell_group = est.groups.cell_group;
    setup.group_count = est.groups.names.size();
  } else if (!setup.metadata.sensors.empty()) {
    notes.push_back("spectra: not estimated: " + layout.why_not);
  }
  for (const std::string& why : layout.skipped) notes.push_back("spectra: no contact force for " + why);
}

// Which accelerometers go to FLAC: a part's step follows from its range; a replay's sensors keep
// the layout they were recorded in (a replayed accel.csv holds decimals, not counts).
std::vector<AccelFlacSensor> accel_flac_sensors(const DaemonConfig& c, const BuiltSources& b, std::vector<std::string>& notes) {
  std::vector<AccelFlacSensor> out;
  if (c.recording.accel_format != "flac") return out;
  if (!b.replaying) {
    for (const AccelConfig& a : c.accelerometers) {
      if (const auto code = accel::Adxl355::range_code(static_cast<int>(a.range_g))) {
        out.push_back({a.id, a.odr_hz, accel::adxl355::mps2_per_lsb(*code)});
      }
    }
    return out;
  }
  for (const auto& path : recording::find_accel_flac(c.replay.recording)) {
    auto info = recording::read_accel_flac_info(path);
    if (!info) {
      notes.push_back("recording: " + info.error().to_string() + "; that sensor goes to accel.csv");
      continue;
    }
    out.push_back({info.value().sensor, info.value().rate_hz, info.value().step_mps2});
  }
  return out;
}

std::optional<RecorderConfig> recorder_config(const DaemonConfig& c, const BuiltSources& b, std::vector<std::string>& notes) {
  const RecordingConfig& r = c.recording;
  if (!r.enabled) return std::nullopt;
  RecorderConfig rc;
  rc.data_dir = r.data_dir;
  rc.fsync_interval = std::chrono::round<Nanoseconds>(r.fsync_interval);
  rc.segment_max = std::chrono::round<Nanoseconds>(r.segment_max);
  rc.segment_max_bytes = static_cast<std::uint64_t>(r.segment_max_mib * 1048576.0);
  rc.quota_bytes = static_cast<std::uint64_t>(r.quota_mib * 1048576.0);
  rc.compression_level = r.compression_level;
  rc.accel_flac = accel_flac_sensors(c, b, notes);
  return rc;
}

// Runs until SIGTERM/SIGINT (or the replays end, with --exit-when-done). SIGHUP reopens the status
// files for logrotate; it must not cut a drive in two, so a new segment takes SIGUSR1.
void serve(Daemon& daemon, StatusLog& log, const CommandLine& cl, const sigset_t& signals) {
  const timespec wait = io::to_timespec(std::chrono::round<Nanoseconds>(cl.config.status.interval));
  for (;;) {
    const int sig = sigtimedwait(&signals, nullptr, &wait);
    if (sig == SIGTERM || sig == SIGINT) return;
    if (sig == SIGHUP) {
      log.reopen();
      continue;
    }
    if (sig == SIGUSR1) {
      daemon.rotate_recording();
      continue;
    }
    const StatusReport r = daemon.report();
    log.text(format_text(r));
    log.json(format_json(r));
    sd_notifyf(0, "WATCHDOG=1\nSTATUS=%zu sources, %zu warnings", r.sources.size(), r.warnings.size());
    if (cl.exit_when_done && daemon.replays_finished()) return;
  }
}

int run(const CommandLine& cl) {
  const DaemonConfig& c = cl.config;
  // Signals are taken synchronously by the main thread; every thread started later inherits the mask.
  sigset_t signals;
  sigemptyset(&signals);
  for (int s : {SIGTERM, SIGINT, SIGHUP, SIGUSR1}) sigaddset(&signals, s);
  pthread_sigmask(SIG_BLOCK, &signals, nullptr);

  // One daemon per data directory, before anything is written there.
  std::optional<io::DirectoryLock> lock;
  if (c.recording.enabled) {
    auto taken = io::DirectoryLock::take(c.recording.data_dir);
    if (!taken) return fail(taken.error().to_string());
    lock.emplace(std::move(taken.value()));
  }
  Estimation est;
  if (auto e = load_estimation(c, est)) return fail(e->to_string());
  io::MonotonicClock clock;
  std::vector<std::string> notes;
  auto built = build_sources(c, clock, notes);
  if (!built) return fail(built.error().to_string());
  StatusLog log(c.status.text_file, c.status.json_file);
  if (!log.open()) return fail("status: " + log.error());

  DaemonSetup setup;
  setup.recording = recorder_config(c, built.value(), notes);
  setup.metadata = metadata(c, built.value(), est.vehicle);
  setup.interfaces = built.value().interfaces;
  setup.buses = built.value().buses;
  if (built.value().replaying && built.value().timing.paced() && built.value().timing.rate != 1.0) {
    setup.timeline = built.value().timing;
  }
  configure_estimator(c, est, setup, notes);
  std::string start = std::string("roadloadd ") + ROADLOAD_VERSION + " started with " + c.source;
  for (const std::string& n : notes) start += "; " + n;
  log.text(start + "\n");
  std::fprintf(stderr, "%s\n", start.c_str());
  Daemon daemon(std::move(setup), std::move(built.value().sources), clock);
  daemon.start();
  sd_notify(0, "READY=1");
  serve(daemon, log, cl, signals);
  sd_notify(0, "STOPPING=1");
  daemon.stop();
  if (!c.estimator.results_dir.empty()) {
    if (auto e = daemon.write_results(c.estimator.results_dir)) log.text("results: " + e->to_string() + "\n");
  }
  const StatusReport last = daemon.report();
  log.text(format_text(last));
  log.json(format_json(last));
  log.text("roadloadd stopped: " + std::to_string(last.recording.lines) + " lines recorded, " +
           std::to_string(last.recording.lines_lost) + " lost\n");
  return last.recording.lines_lost == 0 ? 0 : 3;
}

}  // namespace

int main(int argc, char** argv) {
  auto cl = parse_command_line(std::vector<std::string>(argv + 1, argv + argc));
  if (!cl) {
    std::fprintf(stderr, "roadloadd: %s\n", cl.error().to_string().c_str());
    return cl.error().file == kCommandLineSource ? kExitUsage : kExitConfig;
  }
  if (!cl.value().print.empty()) {
    std::fputs(cl.value().print.c_str(), stdout);
    return 0;
  }
  if (cl.value().print_config) {
    std::fputs(format_config(cl.value().config).c_str(), stdout);
    return 0;
  }
  return run(cl.value());
}
