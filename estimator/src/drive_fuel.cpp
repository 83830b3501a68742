#include "roadload/drive_fuel.hpp"

#include "roadload/model/longitudinal.hpp"

namespace roadload {

// The interval's mean speed meets the air; grade as the profile gives it (its error is the
// filter's to carry, not the breakdown's).
void DriveFuel::fill_resistances(Interval& i, double mass_kg, const CrrFilter::Vec& x) {
  PowerInterval& p = i.power;
  const double v = 0.5 * (p.speed_from_mps + p.speed_to_mps);
  const model::Resistances r = model::resistances(mass_kg, x(CrrState::crr), x(CrrState::cda), i.air_density_kgpm3,
                                                  v + i.headwind_mps, i.grade_rad);
  p.aero_n = r.aero_n;
  p.rolling_n = r.rolling_n;
  p.grade_n = r.grade_n;
}

}  // namespace roadload
