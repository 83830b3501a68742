#pragma once
// The ECU's torque scale from powered drives and coast-downs in neutral over the same cells. A
// coasting tick owes its force balance nothing of the engine (drive_signals.hpp), so its CRR is
// the same whatever scale the analysis holds; a powered drive's CRR moves with the scale by the
// tractive force over the weight. The scale at which each cell's two CRRs agree is the ECU's.
// The sensitivities come from the estimator itself, each drive analysed with the scale held at 0
// and one step off (analyse_for_aero), as the CdA fit takes its own.
#include <cstddef>
#include <span>

#include "roadload/aero_calibration.hpp"

namespace roadload {

struct ScalePair {
  const AeroDrive* powered = nullptr;
  const AeroDrive* coasting = nullptr;
};

struct TorqueScaleCalibration {
  // The truck's tractive force is EEC1's indicated torque times (1 + scale): the value `roadload
  // analyze --torque-scale` holds.
  double scale = 0, sigma = 0;
  // The parts of sigma: cells' scatter, CdA, flywheel torque, and the mass's prior (each drive's
  // own, one sigma up in both: the same truck, the same declared load).
  double statistical = 0, cda = 0, torque = 0, mass = 0;
  double scale_per_cda_m2 = 0;     // how the fit follows an error of the CdA both drives held
  double scale_per_torque_nm = 0;  // and of the flywheel torque (the engine-loss table)
  double chi2_per_dof = 0, residual_correlation = 0;
  std::size_t cells = 0;
  // Where the CdA held came from a fit at a scale of 0 (calibrate --aero), its own value at the
  // fitted scale is that CdA plus this (with_aero_coupling).
  double cda_shift_m2 = 0;
};

// Weighted least squares over the cells each pair's drives both estimated. `cda_sigma_m2` and
// `torque_sigma_nm` are the sigmas of the CdA and the flywheel torque both drives were analysed
// with: the drives meet the drag and the engine's losses at other speeds and loads, so their
// errors pass into the scale; so does the mass, where the drives have a mass run (a coast-down's
// CRR is its deceleration less the drag over the mass, which its own drive barely tells). Nothing (cells 0) when fewer than two cells
// are shared or a 10 % scale would move them by less than one cell's sigma in all.
TorqueScaleCalibration fit_torque_scale(std::span<const ScalePair> pairs, double cda_sigma_m2, double torque_sigma_nm);

// The CdA both drives held was fitted from two speeds at a scale of 0, and moves with the scale by
// `cda_per_torque_scale_m2` (AeroCalibration): the scale k and that CdA c0 + C k solve both fits
// at once, k = k0 / (1 - P C) with P the scale's own slope per CdA, and the sigma, the CdA's
// share included, grows by the same factor. Nothing (cells 0) when P C comes near 1: the two
// calibrations then see one effect, as a powered drive at one speed does.
TorqueScaleCalibration with_aero_coupling(TorqueScaleCalibration fit, double cda_per_torque_scale_m2);

}  // namespace roadload
