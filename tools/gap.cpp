// roadload gap: where the gap between the simulator and a real drive lies, which unmodelled
// effect causes it and how far it shrinks once that effect is added (docs/gap.md).
#include <array>
#include <cstdio>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include <CLI/CLI.hpp>

#include "command.hpp"
#include "files.hpp"
#include "gap_commands.hpp"
#include "roadload/cli/help.hpp"
#include "roadload/cli/values.hpp"
#include "roadload/definitions.hpp"
#include "roadload/gap/engine.hpp"
#include "roadload/gap/library_cache.hpp"
#include "roadload/gap/model_choice.hpp"
#include "roadload/gap/output.hpp"
#include "roadload/route_file.hpp"

namespace roadload::cli {
namespace {

const HelpText kGapHelp{
    "usage: roadload gap --real RECORDING [--real RECORDING ...] [options]\n"
    "       roadload gap bench [--cases N] [--seed S] [--jobs N]\n"
    "       roadload gap tables [--jobs N]",
    "Diagnoses the gap between the simulator and recorded drives: re-simulates each drive from what\n"
    "its recording says (route, speed, weather, mass, driving before it), ranks where real and\n"
    "simulated channels differ beyond a calibrated noise floor, fits every effect of `roadload\n"
    "simulate --list-effects` that its features can see (and pairs) on half of the road's cells,\n"
    "judges them on the other half, names the best or none (with the rivals it cannot tell from it),\n"
    "and re-simulates with it to show how far the gap shrinks on held-out cells.\n"
    "Only the recordings are read: never a simulation's ground truth.",
    "bench: generates drives with effects the diagnosis is not told (one or two at random\n"
    "magnitudes within their ranges, or none), diagnoses them blind and prints the confusion matrix,\n"
    "top-1 accuracy, held-out shrink and false alarms; the last line reads\n"
    "cases=N top1=F shrink=F false_alarm=F.\n"
    "tables: the seed report's Tables 6.5-6.6 (suspension power by pavement) against an IRI-only\n"
    "simulation, the candidate effects that could close the difference, and the tables after."};

struct DiagnosisOptions {
  std::vector<std::string> reals, models;
  std::string json, features, vehicle_name, route_name, holdout = "cells", cache_dir = gap::default_cache_dir();
  gap::GapOptions options;
  bool quiet = false, dry_run = false, no_cache = false;
};

// The runs and the model they are compared with.
void add_runs(CLI::App& cmd, DiagnosisOptions& o) {
  cmd.add_option("--real", o.reals, "recording folder; repeat for several runs of the same truck")->type_name("DIR");
  cmd.add_option("--model", o.models,
                 "scenario (built-in name or TOML file) for the runs, in order; one for\n"
                 "all, or none: the built-in scenario whose route the drive's first GNSS\n"
                 "fix lies on and whose speed is nearest, else a cruise on the road the\n"
                 "drive's own GNSS traces (gnss.csv; cells of 250 m, the heights of that\n"
                 "one pass); a run whose driveline is disengaged (ETC1) 80 % of the time\n"
                 "is a coast-down from its first speed, on a coast scenario of its route\n"
                 "when one exists")
      ->type_name("S");
  cmd.add_option("--route", o.route_name,
                 "route file or built-in route name the runs drove (your own GNSS or GIS\n"
                 "sections): the model cruises it from where each drive starts")
      ->type_name("R");
  cmd.add_option("--vehicle", o.vehicle_name,
                 "vehicle file or built-in name the model drives (default: the one each\n"
                 "recording carries, else the scenario's)")
      ->type_name("V");
  cmd.add_option("--holdout", o.holdout,
                 "what the fit never sees: cells (every other cell, default) or runs\n"
                 "(fit on the 1st, 3rd, ... runs, judge on the 2nd, 4th, ...)")
      ->type_name("H")
      ->check(one_of({"cells", "runs"}));
  cmd.add_option("--noise-runs", o.options.noise_runs, "model seeds calibrating the noise floor (default 8)")
      ->type_name("K")
      ->transform(whole_in(3, 64));
}

// What is written, kept and shown.
void add_outputs(CLI::App& cmd, DiagnosisOptions& o) {
  cmd.add_option("--json", o.json, "write the diagnosis as JSON (docs/gap.md)")->type_name("FILE");
  cmd.add_option("--features", o.features, "write every feature (real, model, noise floor, z, after) as CSV")->type_name("FILE");
  cmd.add_option("--cache", o.cache_dir,
                 "where response libraries are kept for later drives of the same truck on\n"
                 "the same road (default $ROADLOAD_CACHE_DIR, else\n"
                 "$XDG_CACHE_HOME/roadload/gap, else ~/.cache/roadload/gap)")
      ->type_name("DIR");
  cmd.add_flag("--no-cache", o.no_cache, "build the library afresh and keep nothing");
  cmd.add_flag("--dry-run", o.dry_run, "print the model each run is compared with, and stop");
  cmd.add_option("--jobs", o.options.jobs, "simulations at once (default: the number of CPUs)")
      ->type_name("N")
      ->transform(whole_in(1, 256));
  cmd.add_flag("-q,--quiet", o.quiet, "no progress on standard error");
}

// The library (read from the cache when one there serves these runs), the diagnosis, and the files
// asked for: {JSON, features CSV}, either empty for none.
int diagnose(const std::vector<gap::RealRun>& runs, const std::vector<std::string>& run_lines, const j1939::Database& db,
             const gap::GapOptions& options, const std::string& cache_dir, bool quiet, const std::array<std::string, 2>& files) {
  gap::CachedLibrary cached = gap::cached_library(cache_dir, runs, db, options);
  for (const std::string& w : cached.warnings) std::fprintf(stderr, "roadload gap: cache: %s\n", w.c_str());
  if (!cached.note.empty() && !quiet) std::fprintf(stderr, "gap: %s\n", cached.note.c_str());
  const gap::ModelLibrary& lib = cached.library;
  const gap::GapResult result = gap::run_gap(lib, runs, db, options);
  gap::print_result(stdout, result, run_lines);
  for (const auto& [path, text] :
       {std::pair{files[0], gap::result_json(result, run_lines)}, std::pair{files[1], gap::features_csv(result)}}) {
    if (path.empty()) continue;
    if (auto err = gap::write_text_file(path, text)) {
      std::fprintf(stderr, "roadload gap: %s\n", err->to_string().c_str());
      return kExitCantCreate;
    }
  }
  return kExitOk;
}

// The runs to diagnose, each described, and whether any line of them was malformed (diagnosed on
// the good lines, and told by the exit status).
struct LoadedRuns {
  std::vector<gap::RealRun> runs;
  std::vector<std::string> run_lines;
  bool malformed = false;
};

int load_run(const std::string& real, const std::string& model_name, const j1939::Database& db, const std::optional<Vehicle>& vehicle,
             const std::string& route_name, LoadedRuns& loaded) {
  auto run = gap::load_real_run(real, model_name, db, vehicle, route_name.empty() ? std::string() : resolve_route(route_name));
  if (!run) {
    std::fprintf(stderr, "roadload gap: %s\n", run.error().to_string().c_str());
    return exit_for(run.error());
  }
  const recording::ErrorLog& bad = run.value().recorded.malformed;
  for (const ParseError& e : bad.kept()) std::fprintf(stderr, "roadload gap: %s\n", e.to_string().c_str());
  if (bad.count() > 0) {
    std::fprintf(stderr, "roadload gap: %s: %llu malformed lines skipped\n", real.c_str(),
                 static_cast<unsigned long long>(bad.count()));
    loaded.malformed = true;
  }
  loaded.run_lines.push_back(gap::describe(run.value()));
  loaded.runs.push_back(std::move(run.value()));
  return kExitOk;
}

int run_diagnosis(DiagnosisOptions& o) {
  const std::vector<std::string>& reals = o.reals;
  const std::vector<std::string>& models = o.models;
  const std::string& route_name = o.route_name;
  gap::GapOptions& options = o.options;
  options.holdout = o.holdout == "runs" ? gap::Holdout::runs : gap::Holdout::cells;
  if (o.no_cache) o.cache_dir.clear();
  if (reals.empty()) return usage_error("gap", "--real is required (a recording folder)");
  if (models.size() > 1 && models.size() != reals.size())
    return usage_error("gap", "give one --model for all runs or one per --real");
  if (!models.empty() && !route_name.empty())
    return usage_error("gap", "--model and --route: give one (a scenario names its own route)");
  if (options.holdout == gap::Holdout::runs && reals.size() < 2)
    return usage_error("gap", "--holdout runs needs at least two --real");
  if (!o.quiet) options.progress = [](const std::string& line) { std::fprintf(stderr, "gap: %s\n", line.c_str()); };

  j1939::Database db;
  if (auto err = load_dbc_file(db, core_dbc_path())) {
    std::fprintf(stderr, "roadload gap: %s\n", err->to_string().c_str());
    return kExitNoInput;
  }
  std::optional<Vehicle> vehicle;
  if (!o.vehicle_name.empty()) {
    auto v = load_vehicle("gap", o.vehicle_name);
    if (const int* rc = std::get_if<int>(&v)) return *rc;
    vehicle = std::move(std::get<Vehicle>(v));
  }
  LoadedRuns loaded;
  for (std::size_t i = 0; i < reals.size(); ++i) {
    const std::string model_name = models.empty() ? std::string() : models[models.size() == 1 ? 0 : i];
    if (const int rc = load_run(reals[i], model_name, db, vehicle, route_name, loaded); rc != kExitOk) return rc;
  }
  const auto& [runs, run_lines, malformed] = loaded;
  if (o.dry_run) {
    for (const std::string& line : run_lines) std::printf("%s\n", line.c_str());
    return malformed ? kExitDataErr : kExitOk;
  }
  const int rc = diagnose(runs, run_lines, db, options, o.cache_dir, o.quiet, {o.json, o.features});
  return rc == kExitOk && malformed ? kExitDataErr : rc;
}

}  // namespace

unsigned default_jobs() { return std::max(1u, std::thread::hardware_concurrency()); }

Run add_gap(CLI::App& roadload) {
  auto o = std::make_shared<DiagnosisOptions>();
  o->options.jobs = default_jobs();
  CLI::App& cmd = *roadload.add_subcommand(
      "gap", "diagnose the sim-to-real gap: where it lies, which unmodelled effect causes it, how far it shrinks");
  describe(cmd, kGapHelp);
  add_runs(cmd, *o);
  add_outputs(cmd, *o);
  cmd.require_subcommand(0, 1);
  const Run bench = add_gap_bench(cmd);
  const Run tables = add_gap_tables(cmd);
  const CLI::App* bench_cmd = cmd.get_subcommand("bench");
  const CLI::App* tables_cmd = cmd.get_subcommand("tables");
  return [o, bench, tables, bench_cmd, tables_cmd] {
    if (bench_cmd->parsed()) return bench();
    if (tables_cmd->parsed()) return tables();
    return run_diagnosis(*o);
  };
}

}  // namespace roadload::cli
