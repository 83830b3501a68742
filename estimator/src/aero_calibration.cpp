#include "roadload/aero_calibration.hpp"

#include <algorithm>
#include <cmath>

namespace roadload {

AeroDrive analyse_for_aero(const AnalyzerConfig& base,
                           const std::function<std::vector<CellResult>(const AnalyzerConfig&)>& analyze) {
  // Held: CdA's prior sigma and the torque calibration's sigma near zero, so that each cell's
  // sigma is its own noise, not the common part this calibration is about.
  AnalyzerConfig held = base;
  held.estimate_cda = false;
  held.filter.truck.cda_sigma_m2 = 1e-6;
  held.filter.truck.engine_losses = base.filter.truck.engine_losses.shifted(0.0, 1e-6);
  AeroDrive d;
  d.held = analyze(held);
  AnalyzerConfig cda = held;
  cda.filter.truck.cda_prior_m2 += kCdaStep_m2;
  d.cda = analyze(cda);
  AnalyzerConfig torque = held;
  torque.filter.truck.engine_losses = base.filter.truck.engine_losses.shifted(-1.0, 1e-6);
  d.torque = analyze(torque);
  return d;
}

AeroCalibration fit_cda(const AeroDrive& a, const AeroDrive& b, double cda_prior_m2, double torque_sigma_nm) {
  AeroCalibration out;
  const std::size_t n = std::min({a.held.size(), b.held.size(), a.cda.size(), b.cda.size(), a.torque.size(), b.torque.size()});
  // Per cell: the two drives' CRR differ by D (c - CdA) at the prior c, where D is the difference
  // of their sensitivities to CdA.
  double swdd = 0, swdx = 0, swta = 0, swtb = 0;
  struct Cell {
    double x, d, w;
  };
  std::vector<Cell> cells;
  for (std::size_t i = 0; i < n; ++i) {
    if (a.held[i].samples == 0 || b.held[i].samples == 0 || a.cda[i].samples == 0 || b.cda[i].samples == 0) continue;
    const double sa = (a.cda[i].crr - a.held[i].crr) / kCdaStep_m2;
    const double sb = (b.cda[i].crr - b.held[i].crr) / kCdaStep_m2;
    const double d = sa - sb;
    const double x = a.held[i].crr - b.held[i].crr;
    const double var = a.held[i].crr_sigma * a.held[i].crr_sigma + b.held[i].crr_sigma * b.held[i].crr_sigma;
    if (!(var > 0) || !std::isfinite(d) || !std::isfinite(x)) continue;
    const double w = 1.0 / var;
    swdd += w * d * d;
    swdx += w * d * x;
    swta += w * (a.torque[i].crr - a.held[i].crr) * d;
    swtb += w * (b.torque[i].crr - b.held[i].crr) * d;
    cells.push_back({x, d, w});
  }
  // Below one sigma of a cell per m^2 of CdA in total, drag and rolling resistance stay confounded.
  if (cells.size() < 2 || swdd < 1.0) return out;
  const double shift = swdx / swdd;  // c - CdA
  double chi2 = 0;
  for (const Cell& c : cells) chi2 += c.w * (c.x - c.d * shift) * (c.x - c.d * shift);
  out.cells = cells.size();
  out.chi2_per_dof = chi2 / static_cast<double>(cells.size() - 1);
  out.cda_m2 = cda_prior_m2 - shift;
  // The cells' estimates are smoothed and correlated along the road: their scatter widens the
  // statistical sigma where it exceeds what their own sigmas say.
  out.statistical_m2 = std::sqrt(std::max(1.0, out.chi2_per_dof) / swdd);
  out.torque_m2 = torque_sigma_nm * std::hypot(swta, swtb) / swdd;
  out.sigma_m2 = std::hypot(out.statistical_m2, out.torque_m2);
  return out;
}

}  // namespace roadload
