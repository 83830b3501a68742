// roadload analyze: CRR per pavement cell from a recording (the force balance in an EKF, then a
// fixed-interval smoother), written as RESULTS/cells.csv, pavements.csv and trip.json. The
// analysis is a library's (tools/analysis), so that Python and the batch runs call the same.
#include <memory>

#include <CLI/CLI.hpp>

#include "command.hpp"
#include "roadload/analysis/analyze.hpp"

namespace roadload::cli {

Run add_analyze(CLI::App& roadload) {
  auto o = std::make_shared<analysis::AnalyzeOptions>();
  CLI::App& cmd = *roadload.add_subcommand(
      "analyze", "estimate CRR along a recorded drive per pavement cell and type (cells.csv, pavements.csv, trip.json)");
  analysis::add_options(cmd, *o);
  return [o] { return analysis::analyze(*o); };
}

}  // namespace roadload::cli
