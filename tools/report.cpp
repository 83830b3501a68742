// roadload report: the results of a drive as one HTML page a pavement engineer opens from disk.
#include <cstdio>
#include <fstream>
#include <optional>
#include <string>

#include "analyze_results.hpp"
#include "command.hpp"
#include "options.hpp"
#include "roadload/report/report_page.hpp"

namespace roadload::cli {
namespace {

constexpr const char* kHelp =
    "usage: roadload report <results> -o report.html [options]\n\n"
    "Draws the results folder of `roadload analyze` or roadloadd --results as one self-contained HTML\n"
    "page (inline SVG, no script, no network): CRR per cell with its 90 % interval, fuel per cell and\n"
    "per trip by force, contact forces per axle, damper and tire power per cell, the spectra with their\n"
    "modes and joint lines, the drive's sync health, and the tables beside them.\n\n"
    "  -o, --out FILE  the page to write\n"
    "  --truth DIR     a simulation's ground truth (`roadload simulate`): drawn beside the estimates\n"
    "  --title TEXT    the page's title (default: roadload: <results>)\n"
    "  -h, --help      this text\n";

}  // namespace

int run_report(Args args) {
  OptionParser opt("report", args);
  std::string results_dir, out, truth_dir, title;
  while (opt.more()) {
    if (opt.help(kHelp)) return kExitOk;
    if (auto o = opt.value("--out")) {
      out = *o;
    } else if (auto o2 = opt.value("-o")) {
      out = *o2;
    } else if (auto t = opt.value("--truth")) {
      truth_dir = *t;
    } else if (auto ti = opt.value("--title")) {
      title = *ti;
    } else if (opt.single_positional(results_dir, "RESULTS folder")) {
    } else if (!opt.failed()) {
      return opt.fail_unknown();
    }
  }
  if (opt.failed()) return kExitUsage;
  if (results_dir.empty()) return opt.fail("a results folder is required");
  if (out.empty()) return opt.fail("-o FILE is required");

  auto results = results::read_results_dir(results_dir);
  if (!results) {
    std::fprintf(stderr, "roadload report: %s\n", results.error().to_string().c_str());
    return exit_for(results.error());
  }
  std::optional<Truth> truth;
  if (!truth_dir.empty()) {
    auto t = read_truth(truth_dir);
    if (!t) {
      std::fprintf(stderr, "roadload report: %s\n", t.error().to_string().c_str());
      return exit_for(t.error());
    }
    truth = std::move(t.value());
  }
  const report::ReportInput in{&results.value(), truth ? &*truth : nullptr, title.empty() ? "roadload: " + results_dir : title};
  std::ofstream page(out, std::ios::binary);
  page << report::render_report(in);
  page.close();
  if (!page) {
    std::fprintf(stderr, "roadload report: %s: could not be written\n", out.c_str());
    return kExitCantCreate;
  }
  std::printf("%s\n", out.c_str());
  return kExitOk;
}

}  // namespace roadload::cli
