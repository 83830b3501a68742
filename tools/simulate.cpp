// roadload simulate: drive the simulated truck over a simulated road and write a recording plus
// its ground truth.
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "command.hpp"
#include "files.hpp"
#include "progress.hpp"
#include "roadload/cli/help.hpp"
#include "roadload/cli/values.hpp"
#include "roadload/definitions.hpp"
#include "roadload/recording/writer.hpp"
#include "roadload/sim/effects.hpp"
#include "roadload/sim/recording_sink.hpp"
#include "roadload/sim/scenario.hpp"
#include "roadload/sim/simulation.hpp"

namespace roadload::cli {
namespace {

const HelpText kSimulateHelp{"usage: roadload simulate --scenario NAME|FILE --out RECORDING [options]",
                             "Simulates the scenario's truck (a vehicle file, config/vehicles) on a road and writes a recording\n"
                             "(docs/recording-format.md)\n"
                             "and, with --truth, the ground truth (true forces, CRR, dissipated powers, per-cell table).",
                             "The same scenario and seed give byte-identical output."};

int list_effects() {
  std::printf("%-22s %-9s %9s %9s %9s  %s\n", "effect", "unit", "typical", "min", "max", "model");
  for (const auto& e : sim::effect_catalog()) {
    std::printf("%-22.*s %-9.*s %9g %9g %9g  %.*s\n", static_cast<int>(e.name.size()), e.name.data(), static_cast<int>(e.unit.size()),
                e.unit.data(), e.typical, e.min, e.max, static_cast<int>(e.summary.size()), e.summary.data());
  }
  return kExitOk;
}

int list_scenarios() {
  for (const auto& name : sim::builtin_scenarios(data_dir())) {
    auto s = sim::load_scenario(name, data_dir());
    std::printf("%-24s %s\n", name.c_str(), s ? s.value().description.c_str() : s.error().to_string().c_str());
  }
  return kExitOk;
}

struct SimulateOptions {
  std::string scenario, out, truth_dir, vehicle, accel_format = "text";
  std::uint64_t seed = 1;
  std::vector<std::string> effects;
  std::optional<double> duration_s;
  bool quiet = false, list_effects = false, list_scenarios = false;
};

void add_options(CLI::App& cmd, SimulateOptions& o) {
  cmd.add_option("--scenario", o.scenario, "built-in scenario name or a scenario TOML file")->type_name("S");
  cmd.add_option("--vehicle", o.vehicle, "vehicle file or built-in name (config/vehicles) instead of the\nscenario's truck")
      ->type_name("V");
  cmd.add_option("--seed", o.seed, "seed of every random process except the road (default 1)")
      ->type_name("N")
      ->transform(whole_in(0, INT64_MAX));
  cmd.add_option("-o,--out", o.out, "recording folder to write")->type_name("DIR");
  cmd.add_option("--truth", o.truth_dir, "ground-truth folder to write (series.csv, axles.csv, cells.csv,\ntruth.toml)")
      ->type_name("DIR");
  cmd.add_option("--effect", o.effects, "switch an effect on with magnitude M (its typical value if omitted);\nrepeatable")
      ->type_name("NAME[=M]");
  cmd.add_option("--duration", o.duration_s, "stop after S simulated seconds")->type_name("S")->check(real_in(0.1, 1e6));
  cmd.add_option("--accel-format", o.accel_format,
                 "the accelerometers as accel.csv (text, default) or as FLAC counts, one\naccel-ID.flac per sensor (flac)")
      ->type_name("FORMAT")
      ->check(CLI::IsMember({"text", "flac"}));
  cmd.add_flag("--list-effects", o.list_effects, "list the effects with unit, typical value and range, then exit");
  cmd.add_flag("--list-scenarios", o.list_scenarios, "list the built-in scenarios, then exit");
  cmd.add_flag("-q,--quiet", o.quiet, "no progress on standard error");
}

// The scenario as the options change it.
std::variant<sim::Scenario, int> scenario_of(const SimulateOptions& o) {
  auto scenario = sim::load_scenario(o.scenario, data_dir());
  if (!scenario) return failed("simulate", scenario.error());
  if (!o.vehicle.empty()) {
    auto v = load_vehicle("simulate", o.vehicle);
    if (const int* rc = std::get_if<int>(&v)) return *rc;
    scenario.value().vehicle = std::move(std::get<Vehicle>(v));
  }
  for (const auto& e : o.effects) {
    if (auto err = scenario.value().effects.parse_and_set(e)) {
      return usage_error("simulate", "--effect " + *err);
    }
  }
  if (o.duration_s) scenario.value().duration = Seconds{*o.duration_s};
  return std::move(scenario.value());
}

std::optional<ParseError> open_truth(const std::string& dir, sim::TruthRecorder& truth) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) return ParseError{dir, 0, "folder", ec.message()};
  return truth.open(dir);
}

void print_summary(const sim::Simulation& simulation, const std::string& name, std::uint64_t seed, const sim::RunSummary& sum,
                   double wall) {
  const sim::FuelSpec& fuel = simulation.plant().truck().fuel;
  std::fprintf(stderr,
               "simulate: %s seed %" PRIu64
               ": %.1f s over %.0f m in %.1f s wall (%.1fx real time); "
               "%" PRIu64 " CAN frames, %" PRIu64 " accelerometer samples, %" PRIu64 " GNSS fixes, %" PRIu64
               " weather samples; fuel %.3f L\n",
               name.c_str(), seed, sum.simulated_s, sum.distance_m, wall, wall > 0 ? sum.simulated_s / wall : 0.0, sum.frames,
               sum.accel_samples, sum.gnss_fixes, sum.weather_samples, sum.ledger.fuel_j / fuel.lhv_jpkg / fuel.density_kgpl);
}

int simulate(const SimulateOptions& o) {
  if (o.list_effects) return list_effects();
  if (o.list_scenarios) return list_scenarios();
  if (o.scenario.empty()) return usage_error("simulate", "--scenario is required");
  if (o.out.empty()) return usage_error("simulate", "--out is required");
  auto scenario = scenario_of(o);
  if (const int* rc = std::get_if<int>(&scenario)) return *rc;
  const sim::Scenario& sc = std::get<sim::Scenario>(scenario);
  j1939::Database db;
  if (auto err = load_dbc_file(db, core_dbc_path())) return failed("simulate", *err, kExitNoInput);
  sim::Simulation simulation(sc, o.seed, db);
  auto writer = recording::RecordingWriter::create(o.out, simulation.metadata());
  if (!writer) return failed("simulate", writer.error(), kExitNoInput);
  if (o.accel_format == "flac") {
    const std::vector<double> steps = simulation.accel_steps_mps2();
    for (const auto& sensor : simulation.metadata().sensors) {
      if (sensor.kind != "accelerometer") continue;
      const auto id = static_cast<std::uint8_t>(sensor.id);
      if (auto err = writer.value().accel_as_flac(id, sensor.rate_hz, steps.at(id))) return failed("simulate", *err, kExitNoInput);
    }
  }
  std::optional<sim::TruthRecorder> truth;
  if (!o.truth_dir.empty()) {
    truth.emplace(simulation.route(), simulation.plant().truck());
    if (auto err = open_truth(o.truth_dir, *truth)) return failed("simulate", *err, kExitNoInput);
  }
  sim::RecordingSink sink(writer.value());
  Progress progress("simulate", o.quiet);
  const sim::RunSummary sum = simulation.run(sink, truth ? &*truth : nullptr, [&](double f) { progress.update(f); });
  progress.finish();
  std::optional<ParseError> err = writer.value().close();
  if (!err && truth) err = truth->finish(simulation.truth_toml());
  if (err) return failed("simulate", *err, kExitDataErr);
  print_summary(simulation, sc.name, o.seed, sum, progress.wall_s());
  return kExitOk;
}

}  // namespace

Run add_simulate(CLI::App& roadload) {
  auto o = std::make_shared<SimulateOptions>();
  CLI::App& cmd = *roadload.add_subcommand("simulate",
                                           "drive the simulated truck over a simulated road; write a recording and its ground truth");
  describe(cmd, kSimulateHelp);
  add_options(cmd, *o);
  return [o] { return simulate(*o); };
}

}  // namespace roadload::cli
