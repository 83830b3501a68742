#pragma once
// What `roadload analyze` was asked for: its options, read by the command and recorded in the
// results' provenance.
#include <optional>
#include <string>
#include <vector>

namespace roadload::cli {

struct AnalyzeOptions {
  std::string recording, route, out, truth_dir, grade_file, losses_file, vehicle;
  double survey_sigma = 0;
  std::optional<double> mass, cda_m2, cda_sigma_m2, cda_torque_correlation, cda_per_torque_scale_m2;
  std::optional<double> torque_scale, torque_scale_sigma;
  std::vector<std::string> dbcs;
  bool quiet = false, estimate_cda = false;
};

}  // namespace roadload::cli
