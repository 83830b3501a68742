#pragma once
// The whole analysis of one drive, as `roadload analyze` runs it, callable in-process: the CLI
// command, the Python module and the batch runs on Dask all run this one function, so their
// results folders cannot differ.
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace roadload::analysis {

// What `roadload analyze` is asked for: the recording, the road and files beside it, and what is
// known of the truck. The results' provenance records it.
struct AnalyzeOptions {
  // As given; then, once joined (one_drive), the segments of the one drive in order.
  std::vector<std::string> recordings;
  std::string route, out, truth_dir, grade_file, losses_file, vehicle;
  double survey_sigma = 0;
  std::optional<double> mass, cda_m2, cda_sigma_m2, cda_torque_correlation, cda_per_torque_scale_m2;
  std::optional<double> torque_scale, torque_scale_sigma;
  std::vector<std::string> dbcs;
  bool quiet = false, estimate_cda = false;
  // The command's tables and summaries on standard output and error; a library caller reads the
  // results folder instead.
  bool report = true;
  // How far along a long drive is, on standard error.
  bool progress = true;
};

// Describes `cmd` as `roadload analyze` (its --help) and binds its arguments and options to `o`:
// the command's and the Python module's (roadload.analyze's keywords are these options).
void add_options(CLI::App& cmd, AnalyzeOptions& o);

// Joins `o.recordings` into one drive, analyses it and writes o.out/cells.csv, pavements.csv,
// trip.json and the PSD files. Returns the command's exit status: 0; 65 when some input was
// malformed (the results are written all the same, the bad lines named); 64, 66 or 73 when
// nothing could be analysed or written. Every error and warning goes through cli::say(), so a
// cli::MessageCapture on the calling thread receives them as "file:line: field: message".
int analyze(AnalyzeOptions o);

}  // namespace roadload::analysis
