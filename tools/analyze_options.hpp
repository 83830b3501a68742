#pragma once
// roadload analyze's options: the recording, the road and files beside it, and what is known of
// the truck, as its command line sets them.
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace roadload::cli {

struct AnalyzeOptions {
  std::string recording, route, out, truth_dir, grade_file, losses_file, vehicle;
  double survey_sigma = 0;
  std::optional<double> mass, cda_m2, cda_sigma_m2, cda_torque_correlation, cda_per_torque_scale_m2;
  std::optional<double> torque_scale, torque_scale_sigma;
  std::vector<std::string> dbcs;
  bool quiet = false, estimate_cda = false;
};

// Describes `cmd` (its --help) and binds its arguments and options to `o`.
void add_analyze_options(CLI::App& cmd, AnalyzeOptions& o);

}  // namespace roadload::cli
