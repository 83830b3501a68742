#pragma once
// What `roadload analyze` was asked for, as its command line sets it: the recording, the road and
// files beside it, and what is known of the truck. The results' provenance records it.
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace roadload::cli {

struct AnalyzeOptions {
  // As given; then, once joined (one_drive), the segments of the one drive in order.
  std::vector<std::string> recordings;
  std::string route, out, truth_dir, grade_file, losses_file, vehicle;
  double survey_sigma = 0;
  std::optional<double> mass, cda_m2, cda_sigma_m2, cda_torque_correlation, cda_per_torque_scale_m2;
  std::optional<double> torque_scale, torque_scale_sigma;
  std::vector<std::string> dbcs;
  bool quiet = false, estimate_cda = false;
};

// Describes `cmd` (its --help) and binds its arguments and options to `o`.
void add_analyze_options(CLI::App& cmd, AnalyzeOptions& o);

}  // namespace roadload::cli
