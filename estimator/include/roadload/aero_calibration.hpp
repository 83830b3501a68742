#pragma once
// CdA from two drives over the same cells at two speeds. At one speed the force balance cannot
// tell CRR from CdA; a pavement's CRR is the same at both, the aero drag is not (v^2), so the CdA
// that makes each cell's CRR agree between the drives is the truck's. Each drive is analysed with
// CdA and the flywheel torque held, then again with each nudged: the cells' sensitivities come from
// the estimator itself, wind, air density and gear included.
#include <cstddef>
#include <functional>
#include <span>
#include <vector>

#include "roadload/drive_analyzer.hpp"

namespace roadload {

// One drive's cells, analysed three ways.
struct AeroDrive {
  std::vector<CellResult> held;    // CdA and the flywheel torque held at the prior
  std::vector<CellResult> cda;     // CdA + kCdaStep_m2
  std::vector<CellResult> torque;  // flywheel torque + 1 N m
  std::vector<CellResult> scale;   // the ECU's torque scale held `scale_step` off (none when 0)
  std::vector<CellResult> mass;    // the mass's prior one sigma up (AeroRuns::with_mass)
  double scale_step = 0;
};

// The CdA fit needs no mass run: each drive estimates its mass. The torque scale's does: a
// coast-down meets the drag over the mass, and its mass is barely told by the drive.
enum class AeroRuns { standard, with_mass };

inline constexpr double kCdaStep_m2 = 0.5;

// Runs `analyze` (a whole drive through a DriveAnalyzer with the given configuration) the three
// ways, a fourth with the torque scale one sigma off when the truck's has a sigma, and a fifth
// with the mass's prior one sigma up when asked and the truck's mass has a sigma. `base`
// carries the engine-loss calibration, without which the two drives' flywheel torques carry
// EEC3's rounding at two engine speeds, and that would be fitted as drag.
AeroDrive analyse_for_aero(const AnalyzerConfig& base, const std::function<std::vector<CellResult>(const AnalyzerConfig&)>& analyze,
                           AeroRuns runs = AeroRuns::standard);

struct AeroCalibration {
  double cda_m2 = 0, sigma_m2 = 0;
  double statistical_m2 = 0, torque_m2 = 0;  // the parts of sigma: cells' scatter, flywheel torque error
  double chi2_per_dof = 0;                   // of the cells' disagreement left at the fitted CdA
  double residual_correlation = 0;           // lag one along the road, 0-0.9 (negative taken as 0)
  double cda_per_torque_bias_m2_per_nm = 0;  // how the fitted CdA follows a flywheel torque bias
  double torque_bias_correlation = 0;        // of the fitted CdA's error with that bias's
  double cda_per_torque_scale_m2 = 0;        // how the fitted CdA follows the ECU's torque scale
  std::size_t cells = 0;
};

// Weighted least squares over the cells both drives estimated. `torque_sigma_nm` is the flywheel
// torque bias's sigma (the engine-loss calibration's), one bias shared by both drives as by every
// later drive of the truck: the fitted CdA's error correlates with it. Nothing (cells 0) when
// fewer than two cells are shared or the speeds are too close to separate drag from rolling
// resistance.
AeroCalibration fit_cda(const AeroDrive& a, const AeroDrive& b, double cda_prior_m2, double torque_sigma_nm);

// Two drives over the same cells at two speeds: one pair of several (a road both ways, each on its
// own direction's route; another day's pair). One CdA fits every pair's cells: each direction's
// wind and grade errors then count once, not as the truck's drag.
struct AeroPair {
  const AeroDrive* slow = nullptr;
  const AeroDrive* fast = nullptr;
};
AeroCalibration fit_cda(std::span<const AeroPair> pairs, double cda_prior_m2, double torque_sigma_nm);

}  // namespace roadload
