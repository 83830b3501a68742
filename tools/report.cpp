// roadload report: the results of a drive as one HTML page a pavement engineer opens from disk.
#include <cstdio>
#include <fstream>
#include <memory>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "command.hpp"
#include "files.hpp"
#include "roadload/cli/help.hpp"
#include "roadload/report/report_page.hpp"
#include "roadload/results/truth_files.hpp"

namespace roadload::cli {
namespace {

const HelpText kReportHelp{"usage: roadload report <results> -o report.html [options]",
                           "Draws the results folder of `roadload analyze` or roadloadd --results as one self-contained HTML\n"
                           "page (inline SVG, no script, no network): CRR per cell with its 90 % interval, fuel per cell and\n"
                           "per trip by force, contact forces per axle, damper and tire power per cell, the spectra with their\n"
                           "modes and joint lines, the drive's sync health, and the tables beside them."};

struct ReportOptions {
  std::string results_dir, out, truth_dir, title;
};

int write_report(const ReportOptions& o) {
  auto results = results::read_results_dir(o.results_dir);
  if (!results) {
    std::fprintf(stderr, "roadload report: %s\n", results.error().to_string().c_str());
    return exit_for(results.error());
  }
  std::optional<results::Truth> truth;
  if (!o.truth_dir.empty()) {
    auto t = results::read_truth(o.truth_dir);
    if (!t) {
      std::fprintf(stderr, "roadload report: %s\n", t.error().to_string().c_str());
      return exit_for(t.error());
    }
    truth = std::move(t.value());
  }
  const report::ReportInput in{&results.value(), truth ? &*truth : nullptr, o.title.empty() ? "roadload: " + o.results_dir : o.title};
  std::ofstream page(o.out, std::ios::binary);
  page << report::render_report(in);
  page.close();
  if (!page) {
    std::fprintf(stderr, "roadload report: %s: could not be written\n", o.out.c_str());
    return kExitCantCreate;
  }
  std::printf("%s\n", o.out.c_str());
  return kExitOk;
}

}  // namespace

Run add_report(CLI::App& roadload) {
  auto o = std::make_shared<ReportOptions>();
  CLI::App& cmd = *roadload.add_subcommand("report", "draw a drive's results as one self-contained HTML page (figures and tables)");
  describe(cmd, kReportHelp);
  cmd.add_option("RESULTS", o->results_dir, "the results folder")->required();
  cmd.add_option("-o,--out", o->out, "the page to write")->type_name("FILE")->required();
  cmd.add_option("--truth", o->truth_dir, "a simulation's ground truth (`roadload simulate`): drawn beside the\nestimates")
      ->type_name("DIR");
  cmd.add_option("--title", o->title, "the page's title (default: roadload: <results>)")->type_name("TEXT");
  return [o] { return write_report(*o); };
}

}  // namespace roadload::cli
