// roadload simulate: drive the simulated truck over a simulated road and write a recording plus
// its ground truth.
#include <chrono>
#include <cinttypes>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include "command.hpp"
#include "options.hpp"
#include "roadload/definitions.hpp"
#include "roadload/recording/writer.hpp"
#include "roadload/sim/recording_sink.hpp"
#include "roadload/sim/effects.hpp"
#include "roadload/sim/scenario.hpp"
#include "roadload/sim/simulation.hpp"

namespace roadload::cli {
namespace {

constexpr const char* kHelp =
    "usage: roadload simulate --scenario NAME|FILE --out RECORDING [options]\n\n"
    "Simulates the MnROAD test truck on a road and writes a recording (docs/recording-format.md)\n"
    "and, with --truth, the ground truth (true forces, CRR, dissipated powers, per-cell table).\n\n"
    "  --scenario S        built-in scenario name or a scenario TOML file\n"
    "  --seed N            seed of every random process except the road (default 1)\n"
    "  --out DIR           recording folder to write\n"
    "  --truth DIR         ground-truth folder to write (series.csv, axles.csv, cells.csv, truth.toml)\n"
    "  --effect NAME[=M]   switch an effect on with magnitude M (its typical value if omitted); repeatable\n"
    "  --duration S        stop after S simulated seconds\n"
    "  --list-effects      list the effects with unit, typical value and range, then exit\n"
    "  --list-scenarios    list the built-in scenarios, then exit\n"
    "  -q, --quiet         no progress on standard error\n"
    "  -h, --help          this text\n\n"
    "The same scenario and seed give byte-identical output.\n";

int list_effects() {
  std::printf("%-22s %-9s %9s %9s %9s  %s\n", "effect", "unit", "typical", "min", "max", "model");
  for (const auto& e : sim::effect_catalog()) {
    std::printf("%-22.*s %-9.*s %9g %9g %9g  %.*s\n", static_cast<int>(e.name.size()), e.name.data(),
                static_cast<int>(e.unit.size()), e.unit.data(), e.typical, e.min, e.max,
                static_cast<int>(e.summary.size()), e.summary.data());
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

}  // namespace

int run_simulate(Args args) {
  OptionParser opt("simulate", args);
  std::string scenario_name, out, truth_dir;
  std::uint64_t seed = 1;
  std::vector<std::string> effects;
  std::optional<double> duration;
  bool quiet = false;
  while (opt.more()) {
    if (opt.flag("-h", "--help")) {
      std::fputs(kHelp, stdout);
      return kExitOk;
    }
    if (opt.flag("--list-effects")) return list_effects();
    if (opt.flag("--list-scenarios")) return list_scenarios();
    if (opt.flag("-q", "--quiet")) {
      quiet = true;
    } else if (auto v = opt.value("--scenario")) {
      scenario_name = *v;
    } else if (auto n = opt.number("--seed", 0, INT64_MAX)) {
      seed = static_cast<std::uint64_t>(*n);
    } else if (auto o = opt.value("--out")) {
      out = *o;
    } else if (auto t = opt.value("--truth")) {
      truth_dir = *t;
    } else if (auto e = opt.value("--effect")) {
      effects.emplace_back(*e);
    } else if (auto d = opt.real("--duration", 0.1, 1e6)) {
      duration = *d;
    } else if (!opt.failed()) {
      return opt.fail_unknown();
    }
  }
  if (opt.failed()) return kExitUsage;
  if (scenario_name.empty()) return opt.fail("--scenario is required");
  if (out.empty()) return opt.fail("--out is required");

  auto scenario = sim::load_scenario(scenario_name, data_dir());
  if (!scenario) {
    std::fprintf(stderr, "roadload simulate: %s\n", scenario.error().to_string().c_str());
    return kExitNoInput;
  }
  for (const auto& e : effects) {
    if (auto err = scenario.value().effects.parse_and_set(e)) return opt.fail("--effect " + *err);
  }
  if (duration) scenario.value().duration = Seconds{*duration};

  j1939::Database db;
  if (auto err = load_dbc_file(db, core_dbc_path())) {
    std::fprintf(stderr, "roadload simulate: %s\n", err->to_string().c_str());
    return kExitNoInput;
  }
  sim::Simulation simulation(scenario.value(), seed, db);
  auto writer = recording::RecordingWriter::create(out, simulation.metadata());
  if (!writer) {
    std::fprintf(stderr, "roadload simulate: %s\n", writer.error().to_string().c_str());
    return kExitNoInput;
  }
  std::optional<sim::TruthRecorder> truth;
  if (!truth_dir.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(truth_dir, ec);
    truth.emplace(simulation.route(), simulation.plant().truck());
    if (auto err = ec ? std::optional<ParseError>(ParseError{truth_dir, 0, "folder", ec.message()}) : truth->open(truth_dir)) {
      std::fprintf(stderr, "roadload simulate: %s\n", err->to_string().c_str());
      return kExitNoInput;
    }
  }
  sim::RecordingSink sink(writer.value());
  const auto wall0 = std::chrono::steady_clock::now();
  // A terminal gets one line redrawn every percent; a log file a line every tenth.
  const bool tty = isatty(STDERR_FILENO) == 1;
  int last_tenth = 0;
  auto progress = [&](double f) {
    if (quiet) return;
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    if (tty) {
      std::fprintf(stderr, "\rsimulate: %3.0f %%  %.0f s wall", f * 100.0, wall);
    } else if (static_cast<int>(f * 10.0 + 1e-9) > last_tenth) {
      last_tenth = static_cast<int>(f * 10.0 + 1e-9);
      std::fprintf(stderr, "simulate: %3d %%  %.0f s wall\n", last_tenth * 10, wall);
    }
  };
  const sim::RunSummary sum = simulation.run(sink, truth ? &*truth : nullptr, progress);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
  if (!quiet && tty) std::fputc('\n', stderr);
  std::optional<ParseError> err = writer.value().close();
  if (!err && truth) err = truth->finish(simulation.truth_toml());
  if (err) {
    std::fprintf(stderr, "roadload simulate: %s\n", err->to_string().c_str());
    return kExitDataErr;
  }
  std::fprintf(stderr,
               "simulate: %s seed %" PRIu64 ": %.1f s over %.0f m in %.1f s wall (%.1fx real time); "
               "%" PRIu64 " CAN frames, %" PRIu64 " accelerometer samples, %" PRIu64 " GNSS fixes, %" PRIu64
               " weather samples; fuel %.3f L\n",
               scenario.value().name.c_str(), seed, sum.simulated_s, sum.distance_m, wall,
               wall > 0 ? sum.simulated_s / wall : 0.0, sum.frames, sum.accel_samples, sum.gnss_fixes,
               sum.weather_samples, sum.ledger.fuel_j / simulation.plant().truck().fuel.lhv_jpkg /
                                        simulation.plant().truck().fuel.density_kgpl);
  return kExitOk;
}

}  // namespace roadload::cli
