#pragma once
// `roadload calibrate --aero`: CdA from pairs of drives at two speeds (calibrate_aero.cpp), and
// `--torque-scale`: the ECU's torque scale from pairs of a powered drive and a coast-down
// (calibrate_torque_scale.cpp). Both analyse each drive as analyse_for_aero does.
#include <optional>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include "command.hpp"
#include "roadload/aero_calibration.hpp"
#include "roadload/j1939/database.hpp"

namespace roadload::cli {

struct AeroOptions {
  std::vector<std::string> recordings;
  std::vector<std::string> routes;  // one per pair, or one for all
  std::string engine_losses, out, vehicle;
  std::optional<double> cda_prior_m2, cda_sigma_m2;
  std::optional<double> cda_per_torque_scale_m2;  // --torque-scale: the --aero fit's coupling
  // The step of the torque scale's run; 0: the vehicle's prior sigma, and no such run without one.
  double scale_step = 0;
  AeroRuns runs = AeroRuns::standard;
};

// The recordings, each analysed the ways the calibrations need, on its pair's route; with the
// CdA and the flywheel torque's prior sigmas they were analysed with. An exit code when they
// cannot be.
struct CalibrationDrives {
  std::vector<AeroDrive> drives;
  double cda_prior_m2 = 0, cda_sigma_m2 = 0, torque_sigma_nm = 0;
};
std::variant<int, CalibrationDrives> calibration_drives(const AeroOptions& o, const j1939::Database& db);

// A calibration's fit as a CSV of its header and one row; an exit code.
int write_fit_csv(const std::string& path, const char* header, std::string_view row);

int run_calibrate_aero(const AeroOptions& o, const j1939::Database& db);
int run_calibrate_torque_scale(const AeroOptions& o, const j1939::Database& db);

}  // namespace roadload::cli
