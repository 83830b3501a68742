#include "roadload/torque_scale_calibration.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "roadload/residual_scatter.hpp"

namespace roadload {
namespace {

// One cell's CRR per unit of a run's step, with the held run as the origin.
double per_step(const std::vector<CellResult>& run, const std::vector<CellResult>& held, std::size_t i, double step) {
  return (run[i].crr - held[i].crr) / step;
}

}  // namespace

TorqueScaleCalibration fit_torque_scale(std::span<const ScalePair> pairs, double cda_sigma_m2, double torque_sigma_nm) {
  TorqueScaleCalibration out;
  // Per cell: the powered drive's CRR less the coasting one's is x at scale 0 and x + s k at
  // scale k, s the difference of their sensitivities to the scale (the coast's is near 0).
  double sss = 0, ssx = 0, ssc = 0, sst = 0, ssm = 0;
  struct Cell {
    double x, s, w;
    bool first;
  };
  std::vector<Cell> cells;
  for (const ScalePair& pair : pairs) {
    const AeroDrive& p = *pair.powered;
    const AeroDrive& c = *pair.coasting;
    if (!(p.scale_step > 0) || !(c.scale_step > 0)) continue;
    const std::size_t n = std::min(
        {p.held.size(), c.held.size(), p.scale.size(), c.scale.size(), p.cda.size(), c.cda.size(), p.torque.size(), c.torque.size()});
    bool first = true;
    for (std::size_t i = 0; i < n; ++i) {
      if (p.held[i].samples == 0 || c.held[i].samples == 0 || p.scale[i].samples == 0 || c.scale[i].samples == 0) continue;
      const double s = per_step(p.scale, p.held, i, p.scale_step) - per_step(c.scale, c.held, i, c.scale_step);
      const double x = p.held[i].crr - c.held[i].crr;
      const double var = p.held[i].crr_sigma * p.held[i].crr_sigma + c.held[i].crr_sigma * c.held[i].crr_sigma;
      if (!(var > 0) || !std::isfinite(s) || !std::isfinite(x)) continue;
      const double w = 1.0 / var;
      sss += w * s * s;
      ssx += w * s * x;
      ssc += w * s * (per_step(p.cda, p.held, i, kCdaStep_m2) - per_step(c.cda, c.held, i, kCdaStep_m2));
      sst += w * s * (per_step(p.torque, p.held, i, 1.0) - per_step(c.torque, c.held, i, 1.0));
      if (p.mass.size() > i && c.mass.size() > i) {
        ssm += w * s * (per_step(p.mass, p.held, i, 1.0) - per_step(c.mass, c.held, i, 1.0));
      }
      cells.push_back({x, s, w, first});
      first = false;
    }
  }
  constexpr double kScaleStep = 0.1;
  if (cells.size() < 2 || sss * kScaleStep * kScaleStep < 1.0) return out;
  out.scale = -ssx / sss;
  std::vector<Residual> residuals;
  for (const Cell& c : cells) residuals.push_back({std::sqrt(c.w) * (c.x + c.s * out.scale), c.first});
  const ResidualScatter scatter = residual_scatter(residuals);
  out.cells = cells.size();
  out.chi2_per_dof = scatter.chi2_per_dof;
  out.residual_correlation = scatter.correlation;
  out.statistical = scatter.sigma(sss);
  // A CdA error e (true less held) would have moved each cell's disagreement by its CdA
  // sensitivity times e; the fit then gives the scale less (ssc / sss) e, and so on for the torque.
  out.scale_per_cda_m2 = -ssc / sss;
  out.scale_per_torque_nm = -sst / sss;
  out.cda = cda_sigma_m2 * std::abs(out.scale_per_cda_m2);
  out.torque = torque_sigma_nm * std::abs(out.scale_per_torque_nm);
  out.mass = std::abs(ssm / sss);  // the mass run is one sigma up already
  out.sigma = std::sqrt(out.statistical * out.statistical + out.cda * out.cda + out.torque * out.torque + out.mass * out.mass);
  return out;
}

TorqueScaleCalibration with_aero_coupling(TorqueScaleCalibration fit, double cda_per_torque_scale_m2) {
  // Below this, the joint solution amplifies each fit's error more than fourfold.
  constexpr double kMinSeparation = 0.25;
  const double separation = 1.0 - fit.scale_per_cda_m2 * cda_per_torque_scale_m2;
  if (fit.cells == 0 || !(separation >= kMinSeparation)) return TorqueScaleCalibration{};
  const double gain = 1.0 / separation;
  fit.scale *= gain;
  fit.sigma *= gain;
  fit.statistical *= gain;
  fit.cda *= gain;
  fit.torque *= gain;
  fit.mass *= gain;
  fit.cda_shift_m2 = cda_per_torque_scale_m2 * fit.scale;
  return fit;
}

}  // namespace roadload
