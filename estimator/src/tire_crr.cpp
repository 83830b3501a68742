#include "roadload/tire_crr.hpp"

#include <cmath>

namespace roadload {

std::optional<TireCrr> tire_crr(const CellResult& cell, double dissipated_w, double relative_error) {
  if (cell.samples == 0 || !(cell.speed_mps > 0) || !(cell.weight_n > 0) || !(cell.crr_sigma > 0) || !std::isfinite(dissipated_w)) {
    return std::nullopt;
  }
  const double interval_z = (cell.crr_hi - cell.crr) / cell.crr_sigma;
  TireCrr t;
  t.dynamic_crr = dissipated_w / (cell.speed_mps * cell.weight_n);
  t.crr = cell.crr - t.dynamic_crr;
  t.sigma = std::hypot(cell.crr_sigma, relative_error * t.dynamic_crr);
  t.lo = t.crr - interval_z * t.sigma;
  t.hi = t.crr + interval_z * t.sigma;
  return t;
}

std::vector<CellResult> with_tire_crr(std::vector<CellResult> cells, const VibrationAnalysis& vibration) {
  for (std::size_t i = 0; i < cells.size(); ++i) {
    CellResult& c = cells[i];
    const DynamicPower p = vibration.cell_power(i);
    const auto t = p.segments > 0 ? tire_crr(c, p.total_w()) : std::nullopt;
    if (!t) continue;
    c.crr = t->crr;
    c.crr_sigma = t->sigma;
    c.crr_lo = t->lo;
    c.crr_hi = t->hi;
  }
  return cells;
}

}  // namespace roadload
