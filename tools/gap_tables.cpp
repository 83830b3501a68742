// roadload gap tables: the seed report's suspension-power tables against the simulator.
#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>

#include <CLI/CLI.hpp>

#include "command.hpp"
#include "gap_commands.hpp"
#include "roadload/cli/help.hpp"
#include "roadload/cli/values.hpp"
#include "roadload/definitions.hpp"
#include "roadload/gap/output.hpp"
#include "roadload/gap/tables.hpp"
#include "roadload/results/json.hpp"

namespace roadload::cli {
namespace {

const HelpText kGapTablesHelp{"usage: roadload gap tables [--json FILE] [--jobs N]",
                              "The seed report's Tables 6.5 and 6.6 (mean suspension power on the Mainline's bituminous and\n"
                              "concrete cells at 30 mph, on TH 66 and TH 10 at 55 mph) against a simulation that knows only\n"
                              "each pavement's IRI. Each candidate effect that acts on the vertical dynamics (joint-faulting,\n"
                              "slab-curl, suspension-friction, tire-pressure) is fitted to the Mainline's concrete-to-bituminous\n"
                              "ratio and judged on the highways' ratio, which it never saw; the best is added and the table\n"
                              "printed before and after. The simulated figure is the simulator's own damper dissipation.\n"
                              "Then each nominal parameter of the truck (mass, CdA, engine friction, driveline efficiency) is\n"
                              "moved one sigma of its vehicle file's spread; for those that move the suspension power, the\n"
                              "choice is made again at both ends of their 90 % interval."};

struct TablesOptions {
  std::string json;
  unsigned jobs = default_jobs();
};

std::string tables_json(const gap::TablesResult& t) {
  std::string j = "{\n  \"rows\": [";
  for (std::size_t i = 0; i < t.rows.size(); ++i) {
    const auto& r = t.rows[i];
    j += std::string(i ? "," : "") + "\n    {\"pavement\": " + results::json_quote(r.name) +
         ", \"report_w\": " + gap::json_number(r.report_w) + ", \"before_w\": " + gap::json_number(r.before_w) +
         ", \"after_w\": " + gap::json_number(r.after_w) + "}";
  }
  j += "\n  ],\n  \"candidates\": [";
  for (std::size_t i = 0; i < t.candidates.size(); ++i) {
    const auto& c = t.candidates[i];
    j += std::string(i ? "," : "") + "\n    {\"effect\": " + results::json_quote(std::string(sim::effect_info(c.effect).name)) +
         ", \"reaches_mainline_ratio\": " + (c.reached ? "true" : "false") + ", \"magnitude\": " + gap::json_number(c.magnitude) +
         ", \"highway_ratio\": " + gap::json_number(c.highway_ratio) + ", \"holdout_error\": " + gap::json_number(c.holdout_error) +
         "}";
  }
  j += "\n  ],\n  \"effect\": ";
  j += t.chosen >= 0
           ? results::json_quote(std::string(sim::effect_info(t.candidates[static_cast<std::size_t>(t.chosen)].effect).name))
           : std::string("null");
  j += ",\n  \"nominal\": [";
  for (std::size_t i = 0; i < t.nominal.size(); ++i) {
    const auto& n = t.nominal[i];
    j += std::string(i ? "," : "") + "\n    {\"name\": " + results::json_quote(n.name) +
         ", \"unit\": " + results::json_quote(n.unit) + ", \"value\": " + gap::json_number(n.value) +
         ", \"sigma\": " + gap::json_number(n.sigma) + ", \"power_per_sigma\": " + gap::json_number(n.power_per_sigma) +
         ", \"ends\": [";
    for (std::size_t k = 0; k < n.ends.size(); ++k) {
      const auto& e = n.ends[k];
      j += std::string(k ? ", " : "") + "{\"value\": " + gap::json_number(e.value) +
           ", \"effect\": " + (e.effect ? results::json_quote(std::string(sim::effect_info(*e.effect).name)) : std::string("null")) +
           ", \"magnitude\": " + gap::json_number(e.magnitude) + ", \"highway_ratio\": " + gap::json_number(e.highway_ratio) + "}";
    }
    j += "]}";
  }
  j += "\n  ]";
  j += ",\n  \"report_mainline_ratio\": " + gap::json_number(gap::kReportMainlineRatio) +
       ",\n  \"report_highway_ratio\": " + gap::json_number(gap::kReportHighwayRatio) + "\n}\n";
  return j;
}

// The truck's nominal parameters: which move the suspension power, and the choice at both ends of
// the 90 % interval of those that do.
void print_nominal(const gap::TablesResult& t) {
  std::printf(
      "\nthe model's truck (vehicle file; the four powers cannot fit it: each road's level is the report's\n"
      "Eq. 2.7 against the simulator's damper dissipation, a scale the ratios take out):\n");
  for (const auto& n : t.nominal) {
    std::printf("  %-22s %.5g +- %.3g%s%s: Mainline suspension power %+.1f %% per sigma", n.name.c_str(), n.value, n.sigma,
                n.unit.empty() ? "" : " ", n.unit.c_str(), 100.0 * n.power_per_sigma);
    if (n.ends.empty()) std::printf(", left at its value\n");
    for (std::size_t k = 0; k < n.ends.size(); ++k) {
      const auto& e = n.ends[k];
      std::printf("%s at %.5g: ", k ? ";" : "\n   ", e.value);
      if (e.effect) {
        std::printf("%s=%.4g, TH 10/TH 66 %.2f", sim::effect_info(*e.effect).name.data(), e.magnitude, e.highway_ratio);
      } else {
        std::printf("no candidate reaches the Mainline ratio");
      }
    }
    if (!n.ends.empty()) std::printf("\n");
  }
  if (std::all_of(t.nominal.begin(), t.nominal.end(), [](const auto& n) { return n.ends.empty(); })) {
    std::printf(
        "  none moves the suspension power by 1 %% at one sigma: the choice holds for any truck within the\n"
        "  vehicle file's spreads\n");
  }
}

void print_tables(const gap::TablesResult& t) {
  const bool chosen = t.chosen >= 0;
  const gap::TableCandidate* c = chosen ? &t.candidates[static_cast<std::size_t>(t.chosen)] : nullptr;
  std::string after = "after";
  if (c) {
    char text[96];
    std::snprintf(text, sizeof text, "+ %s=%.4g", sim::effect_info(c->effect).name.data(), c->magnitude);
    after = text;
  }
  std::printf("\nsuspension power, W (report: Eq. 2.7 on measured accelerations; simulator: its damper dissipation)\n");
  std::printf("  %-34s %9s %10s %26s\n", "pavement", "report", "IRI only", after.c_str());
  for (const auto& r : t.rows) std::printf("  %-34s %9.0f %10.0f %26.0f\n", r.name.c_str(), r.report_w, r.before_w, r.after_w);
  std::printf("  %-34s %9.2f %10.2f %26.2f  (fitted)\n", "Mainline concrete / bituminous", gap::kReportMainlineRatio,
              t.rows[1].before_w / t.rows[0].before_w, t.rows[1].after_w / t.rows[0].after_w);
  std::printf("  %-34s %9.2f %10.2f %26.2f  (held out)\n", "TH 10 / TH 66", gap::kReportHighwayRatio,
              t.rows[3].before_w / t.rows[2].before_w, t.rows[3].after_w / t.rows[2].after_w);
  std::printf("\ncandidates (Mainline concrete/bituminous ratio by magnitude; fitted to %.2f; TH 10/TH 66 held out, report %.2f):\n",
              gap::kReportMainlineRatio, gap::kReportHighwayRatio);
  for (const auto& cand : t.candidates) {
    const auto& info = sim::effect_info(cand.effect);
    std::printf("  %-20s", info.name.data());
    for (const auto& [m, r] : cand.mainline_ratio) std::printf("  %.4g:%.2f", m, r);
    if (cand.reached) {
      std::printf("  -> %.4g %s, TH 10/TH 66 %.2f (error %.0f %%)\n", cand.magnitude, info.unit.data(), cand.highway_ratio,
                  100.0 * cand.holdout_error);
    } else {
      std::printf("  -> cannot reach %.2f in its range (closest at %.4g; TH 10/TH 66 there %.2f)\n", gap::kReportMainlineRatio,
                  cand.magnitude, cand.highway_ratio);
    }
  }
  if (c) {
    std::printf("\neffect: %s = %.4g %s closes the Mainline gap and predicts the highways' ratio within %.0f %%\n",
                sim::effect_info(c->effect).name.data(), c->magnitude, sim::effect_info(c->effect).unit.data(),
                100.0 * c->holdout_error);
  } else {
    std::printf("\neffect: none of the candidates reaches the report's Mainline ratio\n");
  }
  print_nominal(t);
}

int run_tables(const TablesOptions& o) {
  const std::string& json = o.json;
  const unsigned jobs = o.jobs;
  j1939::Database db;
  if (auto err = load_dbc_file(db, core_dbc_path())) {
    std::fprintf(stderr, "roadload gap tables: %s\n", err->to_string().c_str());
    return kExitNoInput;
  }
  auto t = gap::compare_tables(data_dir(), db, jobs, [](const std::string& line) { std::fprintf(stderr, "gap %s\n", line.c_str()); });
  if (!t) {
    std::fprintf(stderr, "roadload gap tables: %s\n", t.error().to_string().c_str());
    return kExitNoInput;
  }
  print_tables(t.value());
  if (!json.empty()) {
    if (auto err = gap::write_text_file(json, tables_json(t.value()))) {
      std::fprintf(stderr, "roadload gap tables: %s\n", err->to_string().c_str());
      return kExitCantCreate;
    }
  }
  return kExitOk;
}

}  // namespace

Run add_gap_tables(CLI::App& gap) {
  auto o = std::make_shared<TablesOptions>();
  CLI::App& cmd = *gap.add_subcommand("tables", "the seed report's suspension-power tables against the simulator");
  describe(cmd, kGapTablesHelp);
  cmd.add_option("--json", o->json, "write the comparison as JSON")->type_name("FILE");
  cmd.add_option("--jobs", o->jobs, "simulations at once (default: the number of CPUs)")->type_name("N")->transform(whole_in(1, 256));
  return [o] { return run_tables(*o); };
}

}  // namespace roadload::cli
