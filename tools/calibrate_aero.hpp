#pragma once
// `roadload calibrate --aero`: CdA from pairs of drives at two speeds (calibrate_aero.cpp).
#include <optional>
#include <string>
#include <vector>

#include "command.hpp"
#include "roadload/j1939/database.hpp"

namespace roadload::cli {

struct AeroOptions {
  std::vector<std::string> recordings;
  std::vector<std::string> routes;  // one per pair, or one for all
  std::string engine_losses, out, vehicle;
  std::optional<double> cda_prior_m2;
};

int run_calibrate_aero(const AeroOptions& o, const j1939::Database& db);

}  // namespace roadload::cli
