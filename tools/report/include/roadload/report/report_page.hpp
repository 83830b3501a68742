#pragma once
// `roadload report`: one self-contained HTML page from a results folder, with the figures and tables
// of the seed report's Chapter 6 (CRR per cell, fuel per cell and per trip, contact forces, dynamic
// rolling resistance, spectra with modes and joint lines) and the drive's sync health.
#include <string>

#include "roadload/results/results_dir.hpp"
#include "roadload/results/truth_files.hpp"

namespace roadload::report {

struct ReportInput {
  const results::ResultsDir* results = nullptr;
  const results::Truth* truth = nullptr;  // a simulation's ground truth, drawn beside the estimates
  std::string title;
};

std::string render_report(const ReportInput& in);

}  // namespace roadload::report
