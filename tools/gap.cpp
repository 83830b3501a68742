// roadload gap: where the gap between the simulator and a real drive lies, which unmodelled
// effect causes it and how far it shrinks once that effect is added (docs/gap.md).
#include <array>
#include <cstdio>
#include <string>
#include <thread>
#include <vector>

#include "command.hpp"
#include "gap_commands.hpp"
#include "options.hpp"
#include "roadload/definitions.hpp"
#include "roadload/gap/engine.hpp"
#include "roadload/gap/library_cache.hpp"
#include "roadload/gap/model_choice.hpp"
#include "roadload/gap/output.hpp"
#include "roadload/route_file.hpp"

namespace roadload::cli {
namespace {

constexpr const char* kHelp =
    "usage: roadload gap --real RECORDING [--real RECORDING ...] [options]\n"
    "       roadload gap bench [--cases N] [--seed S] [--jobs N]\n"
    "       roadload gap tables [--jobs N]\n\n"
    "Diagnoses the gap between the simulator and recorded drives: re-simulates each drive from what\n"
    "its recording says (route, speed, weather, mass), ranks where real and simulated channels\n"
    "differ beyond a calibrated noise floor, fits every candidate effect of `roadload simulate\n"
    "--list-effects` (and pairs) on half of the road's cells, judges them on the other half, names\n"
    "the best or none, and re-simulates with it to show how far the gap shrinks on held-out cells.\n"
    "Only the recordings are read: never a simulation's ground truth.\n\n"
    "  --real DIR          recording folder; repeat for several runs of the same truck\n"
    "  --model S           scenario (built-in name or TOML file) for the runs, in order; one for all,\n"
    "                      or none: the built-in scenario whose route the drive's first GNSS fix lies\n"
    "                      on and whose speed is nearest, else a cruise on the road the drive's own\n"
    "                      GNSS traces (gnss.csv; cells of 250 m, the heights of that one pass); a run\n"
    "                      whose driveline is disengaged (ETC1) 80 % of the time is a coast-down\n"
    "                      from its first speed, on a coast scenario of its route when one exists\n"
    "  --route R           route file or built-in route name the runs drove (your own GNSS or GIS\n"
    "                      sections): the model cruises it from where each drive starts\n"
    "  --vehicle V         vehicle file or built-in name the model drives (default: the one each\n"
    "                      recording carries, else the scenario's)\n"
    "  --holdout H         what the fit never sees: cells (every other cell, default) or runs\n"
    "                      (fit on the 1st, 3rd, ... runs, judge on the 2nd, 4th, ...)\n"
    "  --json FILE         write the diagnosis as JSON (docs/gap.md)\n"
    "  --features FILE     write every feature (real, model, noise floor, z, after) as CSV\n"
    "  --noise-runs K      model seeds calibrating the noise floor (default 8)\n"
    "  --cache DIR         where response libraries are kept for later drives of the same truck on\n"
    "                      the same road (default $ROADLOAD_CACHE_DIR, else $XDG_CACHE_HOME/roadload/gap,\n"
    "                      else ~/.cache/roadload/gap)\n"
    "  --no-cache          build the library afresh and keep nothing\n"
    "  --dry-run           print the model each run is compared with, and stop\n"
    "  --jobs N            simulations at once (default: the number of CPUs)\n"
    "  -q, --quiet         no progress on standard error\n"
    "  -h, --help          this text\n\n"
    "bench: generates drives with effects the diagnosis is not told (one or two at random\n"
    "magnitudes within their ranges, or none), diagnoses them blind and prints the confusion matrix,\n"
    "top-1 accuracy, held-out shrink and false alarms; the last line reads\n"
    "cases=N top1=F shrink=F false_alarm=F.\n"
    "tables: the seed report's Tables 6.5-6.6 (suspension power by pavement) against an IRI-only\n"
    "simulation, the candidate effects that could close the difference, and the tables after.\n";

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

int run_diagnosis(OptionParser& opt) {
  std::vector<std::string> reals, models;
  std::string json, features, vehicle_name, route_name, cache_dir = gap::default_cache_dir();
  gap::GapOptions options;
  options.jobs = default_jobs();
  bool quiet = false, dry_run = false;
  while (opt.more()) {
    if (opt.help(kHelp)) return kExitOk;
    if (opt.flag("-q", "--quiet")) {
      quiet = true;
    } else if (auto r = opt.value("--real")) {
      reals.emplace_back(*r);
    } else if (auto m = opt.value("--model")) {
      models.emplace_back(*m);
    } else if (auto v = opt.value("--vehicle")) {
      vehicle_name = *v;
    } else if (auto rt = opt.value("--route")) {
      route_name = *rt;
    } else if (auto j = opt.value("--json")) {
      json = *j;
    } else if (auto c = opt.value("--cache")) {
      cache_dir = *c;
    } else if (opt.flag("--no-cache")) {
      cache_dir.clear();
    } else if (opt.flag("--dry-run")) {
      dry_run = true;
    } else if (auto f = opt.value("--features")) {
      features = *f;
    } else if (auto h = opt.value("--holdout")) {
      if (*h != "cells" && *h != "runs") return opt.fail("--holdout: expected cells or runs, not '" + std::string(*h) + "'");
      options.holdout = *h == "runs" ? gap::Holdout::runs : gap::Holdout::cells;
    } else if (auto k = opt.number("--noise-runs", 3, 64)) {
      options.noise_runs = static_cast<std::size_t>(*k);
    } else if (auto n = opt.number("--jobs", 1, 256)) {
      options.jobs = static_cast<unsigned>(*n);
    } else if (!opt.failed()) {
      return opt.fail_unknown();
    }
  }
  if (opt.failed()) return kExitUsage;
  if (reals.empty()) return opt.fail("--real is required (a recording folder)");
  if (models.size() > 1 && models.size() != reals.size()) return opt.fail("give one --model for all runs or one per --real");
  if (!models.empty() && !route_name.empty()) return opt.fail("--model and --route: give one (a scenario names its own route)");
  if (options.holdout == gap::Holdout::runs && reals.size() < 2) return opt.fail("--holdout runs needs at least two --real");
  if (!quiet) options.progress = [](const std::string& line) { std::fprintf(stderr, "gap: %s\n", line.c_str()); };

  j1939::Database db;
  if (auto err = load_dbc_file(db, core_dbc_path())) {
    std::fprintf(stderr, "roadload gap: %s\n", err->to_string().c_str());
    return kExitNoInput;
  }
  std::optional<Vehicle> vehicle;
  if (!vehicle_name.empty()) {
    auto v = load_vehicle("gap", vehicle_name);
    if (const int* rc = std::get_if<int>(&v)) return *rc;
    vehicle = std::move(std::get<Vehicle>(v));
  }
  LoadedRuns loaded;
  for (std::size_t i = 0; i < reals.size(); ++i) {
    const std::string model_name = models.empty() ? std::string() : models[models.size() == 1 ? 0 : i];
    if (const int rc = load_run(reals[i], model_name, db, vehicle, route_name, loaded); rc != kExitOk) return rc;
  }
  const auto& [runs, run_lines, malformed] = loaded;
  if (dry_run) {
    for (const std::string& line : run_lines) std::printf("%s\n", line.c_str());
    return malformed ? kExitDataErr : kExitOk;
  }
  const int rc = diagnose(runs, run_lines, db, options, cache_dir, quiet, {json, features});
  return rc == kExitOk && malformed ? kExitDataErr : rc;
}

}  // namespace

unsigned default_jobs() { return std::max(1u, std::thread::hardware_concurrency()); }

int run_gap(Args args) {
  if (!args.empty() && std::string_view(args[0]) == "bench") {
    OptionParser opt("gap bench", args.subspan(1));
    return run_gap_bench(opt);
  }
  if (!args.empty() && std::string_view(args[0]) == "tables") {
    OptionParser opt("gap tables", args.subspan(1));
    return run_gap_tables(opt);
  }
  OptionParser opt("gap", args);
  return run_diagnosis(opt);
}

}  // namespace roadload::cli
