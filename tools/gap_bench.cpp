// roadload gap bench: the diagnosis tried blind on drives with hidden effects.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "command.hpp"
#include "gap_commands.hpp"
#include "roadload/cli/help.hpp"
#include "roadload/cli/values.hpp"
#include "roadload/definitions.hpp"
#include "roadload/gap/bench.hpp"

namespace roadload::cli {
namespace {

const HelpText kGapBenchHelp{
    "usage: roadload gap bench [--cases N] [--seed S] [--effects A,B,...] [--days FILE] [--road NAME]\n"
    "                          [--model-truck] [--case K ...] [--jobs N]",
    "Simulates test days of a truck (each on one road: two cruise runs and a neutral coast-down, as\n"
    "a test-days file sets them out) with effects the diagnosis is not told: one at a random\n"
    "magnitude within its range, two at once (15 % of cases) or none (20 %). Each day is diagnosed\n"
    "blind, from what its recordings would hold.\n"
    "Prints every case, the confusion matrix, top-1 accuracy (null runs count as right when nothing\n"
    "is named), the mean held-out shrink over cases whose effect is visible above the noise, and\n"
    "the false-alarm rate on null runs. The last line reads\n"
    "cases=N top1=F shrink=F false_alarm=F.\n"
    "--case runs only the cases named, as numbered in a run of the whole draw; their model library is\n"
    "built for them alone, so their figures can differ a little from that run's."};

std::string name_of(sim::Effect e) { return std::string(sim::effect_info(e).name); }

// --effects: a comma-separated list or "all"; the first unknown name, when there is one.
std::optional<std::string> parse_effects(std::string_view list, std::vector<sim::Effect>& out) {
  if (list == "all") {
    for (const auto& e : sim::effect_catalog()) out.push_back(e.id);
    return std::nullopt;
  }
  while (!list.empty()) {
    const auto comma = list.find(',');
    const std::string_view name = list.substr(0, comma);
    const auto e = sim::find_effect(name);
    if (!e) return std::string(name);
    out.push_back(*e);
    list = comma == std::string_view::npos ? std::string_view() : list.substr(comma + 1);
  }
  return std::nullopt;
}

// The days the cases are drawn from.
struct DaysChoice {
  std::string file;
  std::vector<std::string> roads;  // empty: every day
};

struct BenchOptions {
  gap::BenchPlan plan;
  gap::GapOptions options;
  DaysChoice days{gap::default_bench_days(data_dir()), {}};
  std::string effects_list;
  bool model_truck = false;
  std::vector<std::size_t> only;  // case numbers, 1-based; empty: every case
};

void add_options(CLI::App& cmd, BenchOptions& o) {
  cmd.add_option("--cases", o.plan.cases, "cases (default 50)")->type_name("N")->transform(whole_in(1, 100000));
  cmd.add_option("--seed", o.plan.seed, "seed of the draw (default 1)")->type_name("S")->transform(whole_in(0, INT64_MAX));
  // Each list is read into the plan as it is checked: an unknown name is a usage error.
  cmd.add_option("--effects", o.effects_list,
                 "effects to draw from, comma-separated, or \"all\" (default: every\neffect the features can see; the others are "
                 "listed with why)")
      ->type_name("LIST")
      ->each([&o](const std::string& list) {
        if (auto bad = parse_effects(list, o.plan.effects))
          throw CLI::ValidationError("unknown effect '" + *bad + "' (roadload simulate --list-effects)");
      });
  cmd.add_option("--days", o.days.file,
                 "test-days file (default: config/bench/test-days.toml: the MnROAD\n"
                 "Mainline, TH 10, TH 66 and a generated hilly road); each case draws one\n"
                 "of its days")
      ->type_name("FILE");
  cmd.add_option("--road", o.days.roads, "only the days on this road (repeatable)")->type_name("NAME");
  cmd.add_flag("--model-truck", o.model_truck,
               "every case drives the model's own truck (default: each case a truck\n"
               "drawn from the vehicle file's spreads of mass, CdA, engine friction and\n"
               "driveline efficiency, whose recovery is scored)");
  cmd.add_option("--case", o.only, "only case K of the draw (repeatable), to look again at it")
      ->type_name("K")
      ->transform(whole_in(1, 100000));
  cmd.add_option("--jobs", o.options.jobs, "simulations at once (default: the number of CPUs)")
      ->type_name("N")
      ->transform(whole_in(1, 256));
}

// For a case looked at again: the truck fitted on half 0 alone and beside each leading single, in
// prior sigmas, which the truck factor and the nominal recovery turn on.
void print_trucks(const gap::CaseOutcome& o) {
  const auto& d = o.result.diagnosis;
  auto line = [&](const std::string& label, const std::vector<std::size_t>& set, const std::vector<double>& magnitudes) {
    const gap::NominalFit f = gap::fit_nominal(o.result.problem, set, magnitudes);
    std::string text;
    for (std::size_t j = 0; j < f.shift_sigma.size(); ++j) {
      char v[64];
      std::snprintf(v, sizeof v, "  %s %+.1f", o.result.problem.nominal[j].name.c_str(), f.shift_sigma[j]);
      text += v;
    }
    std::printf("      truck %s (half 0):%s\n", label.c_str(), text.c_str());
  };
  line("alone", {}, {});
  for (std::size_t k = 0; k < d.singles.size() && k < 4; ++k) {
    line("beside " + o.result.problem.candidates[d.singles[k].effects[0]].name, d.singles[k].effects, d.singles[k].magnitude_half0);
  }
}

void print_case(std::size_t i, const gap::CaseOutcome& o) {
  const auto& d = o.result.diagnosis;
  char shrink[16] = "-";
  if (o.visible) std::snprintf(shrink, sizeof shrink, "%.2f", o.shrink);
  std::printf("%4zu  %-48s %-44s %8.1f %7s %s\n", i + 1, gap::describe_effects(o.truth.effects).c_str(),
              gap::named_effects(o).c_str(), d.singles.empty() ? 0.0 : d.singles.front().gain, shrink,
              o.named_right   ? ""
              : o.rival_right ? "  <- wrong (hidden among its rivals)"
                              : "  <- wrong");
  // The truck: each parameter's truth and fit in its prior sigmas, off the model's value.
  std::string truck;
  for (std::size_t j = 0; j < o.nominal_truth.size(); ++j) {
    const gap::NominalColumn& c = o.result.problem.nominal[j];
    char text[96];
    std::snprintf(text, sizeof text, "  %s %+.1f -> %+.1f%s", c.name.c_str(), (o.nominal_truth[j] - c.value) / c.sigma,
                  d.nominal.shift_sigma[j], o.nominal_covered[j] ? "" : "!");
    truck += text;
  }
  std::printf("      %s; truck (sigmas, true -> fitted; ! outside the interval):%s\n", o.road.c_str(), truck.c_str());
  const double linear_truck = gap::fit_nominal(o.result.problem, {}, {}).chi2_half1_after;
  const double linear_after = d.chosen
                                  ? gap::fit_nominal(o.result.problem, d.chosen->effects, d.chosen->magnitude_half0).chi2_half1_after
                                  : linear_truck;
  std::printf(
      "      held-out chi-square: %.0f as modelled, %.0f (%.0f) with the truck fitted, %.0f (%.0f) with the effect; in "
      "brackets: linear; noise drives %.0f +- %.0f\n",
      o.result.chi2_raw, o.result.chi2_before, linear_truck, o.result.chi2_after, linear_after, o.result.null_chi2_mean,
      o.result.null_chi2_sd);
  // The leading candidates and any hidden effect behind them, so that a decision rule can be
  // judged from the bench's output without simulating again.
  std::string lead;
  for (std::size_t k = 0; k < d.singles.size(); ++k) {
    const gap::Candidate& c = o.result.problem.candidates[d.singles[k].effects[0]];
    const bool hidden = std::any_of(o.truth.effects.begin(), o.truth.effects.end(),
                                    [&](const auto& e) { return sim::effect_info(e.first).name == c.name; });
    if (k >= 4 && !hidden) continue;
    char text[160];
    std::snprintf(text, sizeof text, "%s %s%s %.1f (%.0f)", lead.empty() ? "" : ",", c.name.c_str(),
                  c.stood_for_by.empty() ? "" : "*", d.singles[k].gain, c.null_gain);
    lead += text;
    if (d.singles[k].truck_plausibility < 0.99) {
      std::snprintf(text, sizeof text, " [truck %.1f sigma: x %.2g; kept %.1f]", d.singles[k].truck_sigma,
                    d.singles[k].truck_plausibility, d.singles[k].gain_truck_kept);
      lead += text;
    }
  }
  if (d.best_pair) {
    char text[160];
    std::snprintf(text, sizeof text, "; pair %s + %s %.1f", o.result.problem.candidates[d.best_pair->effects[0]].name.c_str(),
                  o.result.problem.candidates[d.best_pair->effects[1]].name.c_str(), d.best_pair->gain);
    lead += text;
  }
  std::printf("      gains (noise drives' most; * never named):%s%s%s\n", lead.c_str(),
              o.result.withheld.empty() ? "" : "; withheld: ", o.result.withheld.c_str());
  std::fflush(stdout);
}

void print_score(const gap::BenchScore& score, std::size_t libraries) {
  std::printf("\nconfusion (rows: hidden effect, the first of a pair marked (+1); columns: first named):\n");
  for (const auto& [row, cols] : score.confusion) {
    std::printf("  %-30s", row.c_str());
    for (const auto& [col, n] : cols) std::printf(" %s:%d", col.c_str(), n);
    std::printf("\n");
  }
  std::printf("\nnominal truck recovered (fitted on half 0; the drawn truck's true values):\n");
  std::size_t covered = 0, total = 0;
  for (const auto& r : score.nominal) {
    const double n = static_cast<double>(std::max<std::size_t>(1, r.cases));
    std::printf("  %-22s inside its 90 %% interval %zu/%zu (%.0f %%), RMS error %.4g %s (prior's %.4g)\n", r.name.c_str(), r.covered,
                r.cases, 100.0 * static_cast<double>(r.covered) / n, std::sqrt(r.error_ss / n), r.unit.c_str(),
                std::sqrt(r.prior_ss / n));
    covered += r.covered;
    total += r.cases;
  }
  if (total > 0) {
    std::printf("  %-22s %zu/%zu (%.1f %%; goal 80-97 %%)\n", "all parameters", covered, total,
                100.0 * static_cast<double>(covered) / static_cast<double>(total));
  }
  std::printf("\ntop-1 by road:");
  for (const auto& [road, n] : score.by_road) std::printf(" %s %zu/%zu", road.c_str(), n.first, n.second);
  std::printf("\ntop-1 %zu/%zu; shrink over %zu visible effect cases; false alarms %zu/%zu null runs; %zu model libraries\n",
              score.right, score.cases, score.visible, score.alarms, score.nulls, libraries);
  std::printf("wrong names %zu, of which %zu had the hidden effect among the rivals the answer lists as not told apart\n",
              score.wrong_names, score.rival_right);
  std::printf("goals: top1 >= 0.90, shrink >= 0.70, false_alarm <= 0.05\n");
  std::printf("cases=%zu top1=%.3f shrink=%.3f false_alarm=%.3f\n", score.cases, score.top1(), score.shrink(), score.false_alarm());
}

int run_bench(BenchOptions& bench) {
  gap::BenchPlan& plan = bench.plan;
  gap::GapOptions& options = bench.options;
  const DaysChoice& choice = bench.days;
  if (bench.model_truck) plan.draw_trucks = false;
  j1939::Database db;
  if (auto err = load_dbc_file(db, core_dbc_path())) {
    std::fprintf(stderr, "roadload gap bench: %s\n", err->to_string().c_str());
    return kExitNoInput;
  }
  auto loaded = gap::load_bench_days(choice.file, data_dir());
  if (!loaded) {
    std::fprintf(stderr, "roadload gap bench: %s\n", loaded.error().to_string().c_str());
    return kExitDataErr;
  }
  std::vector<gap::BenchDay> days;
  for (auto& d : loaded.value()) {
    if (choice.roads.empty() || std::find(choice.roads.begin(), choice.roads.end(), d.road) != choice.roads.end()) {
      days.push_back(std::move(d));
    }
  }
  if (days.empty()) {
    std::fprintf(stderr, "roadload gap bench: --road: no day of %s drives it\n", choice.file.c_str());
    return kExitUsage;
  }
  options.progress = [](const std::string& line) { std::fprintf(stderr, "gap bench: %s\n", line.c_str()); };
  const auto cases = gap::draw_cases(plan, days);
  for (const std::size_t k : bench.only) {
    if (k > cases.size()) {
      std::fprintf(stderr, "roadload gap bench: --case %zu: the draw has %zu cases (--cases)\n", k, cases.size());
      return kExitUsage;
    }
  }
  auto chosen = [&](std::size_t i) {
    return bench.only.empty() || std::find(bench.only.begin(), bench.only.end(), i + 1) != bench.only.end();
  };
  std::size_t runs = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) runs += chosen(i) ? 1 : 0;
  if (plan.effects.empty()) {
    for (const auto& e : sim::effect_catalog()) {
      if (const char* why = gap::unobservable(e.id)) std::printf("not drawn: %s: %s\n", name_of(e.id).c_str(), why);
    }
    std::printf("\n");
  }
  std::vector<gap::ModelLibrary> libraries;
  gap::BenchScore score;
  const auto wall0 = std::chrono::steady_clock::now();
  std::printf("%4s  %-48s %-44s %8s %7s\n", "case", "hidden effects", "named (fitted magnitude)", "gain", "shrink");
  std::size_t done = 0;
  for (std::size_t i = 0; i < cases.size(); ++i) {
    if (!chosen(i)) continue;
    const gap::CaseOutcome o = gap::run_case(cases[i], days, libraries, db, options);
    score.add(o);
    print_case(i, o);
    if (!bench.only.empty()) print_trucks(o);
    ++done;
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    const double left = wall / static_cast<double>(done) * static_cast<double>(runs - done);
    std::fprintf(stderr, "gap bench: %zu/%zu cases, %.0f s, about %.0f s left\n", done, runs, wall, left);
  }
  print_score(score, libraries.size());
  return kExitOk;
}

}  // namespace

Run add_gap_bench(CLI::App& gap) {
  auto o = std::make_shared<BenchOptions>();
  o->options.jobs = default_jobs();
  CLI::App& cmd = *gap.add_subcommand("bench", "the diagnosis tried blind on simulated drives with hidden effects");
  describe(cmd, kGapBenchHelp);
  add_options(cmd, *o);
  return [o] { return run_bench(*o); };
}

}  // namespace roadload::cli
