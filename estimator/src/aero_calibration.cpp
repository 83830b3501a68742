#include "roadload/aero_calibration.hpp"

#include <algorithm>
#include <cmath>

#include "roadload/residual_scatter.hpp"

namespace roadload {

AeroDrive analyse_for_aero(const AnalyzerConfig& base, const std::function<std::vector<CellResult>(const AnalyzerConfig&)>& analyze,
                           AeroRuns runs) {
  // Held: CdA's prior sigma and the torque calibration's sigma near zero, so that each cell's
  // sigma is its own noise, not the common part this calibration is about.
  AnalyzerConfig held = base;
  held.estimate_cda = false;
  held.filter.truck.cda_sigma_m2 = 1e-6;
  held.filter.truck.engine_losses = base.filter.truck.engine_losses.shifted(0.0, 1e-6);
  // As `roadload analyze` runs first: the torque scale held exact (its sigma is carried by a second
  // run there, torque_scale_consider.hpp) and the mass estimated, so the CdA found is the one at
  // which analyze's own cells agree across speeds. The mass moves little with each trial CdA now
  // that the route's grade comes with its sigma; held at a declared mass a few percent off, the
  // grade's force was fitted as drag (CdA 16 % high on one new-road seed).
  held.filter.truck.torque_scale_sigma = 0;
  AeroDrive d;
  d.held = analyze(held);
  AnalyzerConfig cda = held;
  cda.filter.truck.cda_prior_m2 += kCdaStep_m2;
  d.cda = analyze(cda);
  AnalyzerConfig torque = held;
  torque.filter.truck.engine_losses = base.filter.truck.engine_losses.shifted(-1.0, 1e-6);
  d.torque = analyze(torque);
  if (base.filter.truck.torque_scale_sigma > 0) {
    AnalyzerConfig scale = held;
    d.scale_step = base.filter.truck.torque_scale_sigma;
    scale.filter.torque_scale_held = base.filter.torque_scale_held + d.scale_step;
    d.scale = analyze(scale);
  }
  if (runs == AeroRuns::with_mass && base.filter.truck.mass_sigma_kg > 0) {
    AnalyzerConfig mass = held;
    mass.filter.truck.mass_kg += base.filter.truck.mass_sigma_kg;
    d.mass = analyze(mass);
  }
  return d;
}

AeroCalibration fit_cda(const AeroDrive& a, const AeroDrive& b, double cda_prior_m2, double torque_sigma_nm) {
  const AeroPair pair[] = {{&a, &b}};
  return fit_cda(pair, cda_prior_m2, torque_sigma_nm);
}

AeroCalibration fit_cda(std::span<const AeroPair> pairs, double cda_prior_m2, double torque_sigma_nm) {
  AeroCalibration out;
  // Per cell: the two drives' CRR differ by D (c - CdA) at the prior c, where D is the difference
  // of their sensitivities to CdA.
  double swdd = 0, swdx = 0, swta = 0, swtb = 0, swsd = 0;
  struct Cell {
    double x, d, w;
    bool first;  // of its pair: no neighbour before it along the road
  };
  std::vector<Cell> cells;
  for (const AeroPair& pair : pairs) {
    const AeroDrive& a = *pair.slow;
    const AeroDrive& b = *pair.fast;
    const std::size_t n = std::min({a.held.size(), b.held.size(), a.cda.size(), b.cda.size(), a.torque.size(), b.torque.size()});
    const bool scaled = a.scale_step > 0 && b.scale_step > 0 && a.scale.size() >= n && b.scale.size() >= n;
    bool first = true;
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
      if (scaled && a.scale[i].samples > 0 && b.scale[i].samples > 0) {
        const double per_scale = (a.scale[i].crr - a.held[i].crr) / a.scale_step - (b.scale[i].crr - b.held[i].crr) / b.scale_step;
        swsd += w * per_scale * d;
      }
      cells.push_back({x, d, w, first});
      first = false;
    }
  }
  // Below one sigma of a cell per m^2 of CdA in total, drag and rolling resistance stay confounded.
  if (cells.size() < 2 || swdd < 1.0) return out;
  const double shift = swdx / swdd;  // c - CdA
  std::vector<Residual> residuals;
  for (const Cell& c : cells) residuals.push_back({std::sqrt(c.w) * (c.x - c.d * shift), c.first});
  const ResidualScatter scatter = residual_scatter(residuals);
  out.cells = cells.size();
  out.chi2_per_dof = scatter.chi2_per_dof;
  out.cda_m2 = cda_prior_m2 - shift;
  // The cells' sigmas overstate how far the two drives disagree (chi2/dof near 0.13 on the
  // simulated Mainline, where the fitted CdA's errors then matched the scatter's sigma).
  out.residual_correlation = scatter.correlation;
  out.statistical_m2 = scatter.sigma(swdd);
  // A flywheel torque bias b (true less computed, the same engine-loss map in both drives) lowers
  // each drive's CRR by its sensitivity times b, so the fit carries CdA + b (swta - swtb) / swdd.
  out.cda_per_torque_bias_m2_per_nm = (swta - swtb) / swdd;
  // Assumed one unit of torque scale off, each cell's disagreement would move by its sensitivity
  // to it, and the fitted CdA with it: the drag of a torque the ECU over- or understates.
  out.cda_per_torque_scale_m2 = -swsd / swdd;
  out.torque_m2 = torque_sigma_nm * std::abs(out.cda_per_torque_bias_m2_per_nm);
  out.sigma_m2 = std::hypot(out.statistical_m2, out.torque_m2);
  // The filter's covariance is of the truth about the estimate: CdA less the fit is -k b.
  out.torque_bias_correlation = out.sigma_m2 > 0 ? -out.cda_per_torque_bias_m2_per_nm * torque_sigma_nm / out.sigma_m2 : 0.0;
  return out;
}

}  // namespace roadload
