#include "roadload/tire_crr.hpp"

#include <cmath>

namespace roadload {

std::optional<TireCrr> tire_crr(const CellResult& cell, double dissipated_w, double interval_z, double relative_error) {
  if (cell.samples == 0 || !(cell.speed_mps > 0) || !(cell.weight_n > 0) || !std::isfinite(dissipated_w)) {
    return std::nullopt;
  }
  TireCrr t;
  t.dynamic_crr = dissipated_w / (cell.speed_mps * cell.weight_n);
  t.crr = cell.crr - t.dynamic_crr;
  t.sigma = std::hypot(cell.crr_sigma, relative_error * t.dynamic_crr);
  t.lo = t.crr - interval_z * t.sigma;
  t.hi = t.crr + interval_z * t.sigma;
  return t;
}

}  // namespace roadload
