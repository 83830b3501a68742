#pragma once
// How far a calibration's cells disagree at its fitted value, and what that makes its statistical
// sigma. The cells' own sigmas overstate the scatter (neighbouring cells share smoothed data, and
// the filter's noise shares are bounds), so the scatter itself sizes the sigma, widened as for
// AR(1) noise where neighbouring cells' residuals correlate along the road.
#include <span>

namespace roadload {

struct Residual {
  double z = 0;        // weighted residual: sqrt(w) (x - d fit)
  bool first = false;  // of its drive or pair: no neighbour before it along the road
};

struct ResidualScatter {
  double chi2_per_dof = 0;
  double correlation = 0;  // lag one, bias-corrected, clamped to 0-0.9
  // The statistical sigma of a one-parameter weighted least-squares fit whose normal sum is `swdd`.
  double sigma(double swdd) const;
};

// Needs two residuals or more (one degree of freedom).
ResidualScatter residual_scatter(std::span<const Residual> residuals);

}  // namespace roadload
