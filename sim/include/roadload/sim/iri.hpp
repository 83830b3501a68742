#pragma once
// International Roughness Index of a generated profile, so the simulator can check its roads against
// the IRI the report gives (TH 10 2.55 m/km, TH 66 2.65 m/km). The G_d <-> IRI mapping for
// ISO 8608 profiles is declared in road_profile.hpp, with the class values.
#include "roadload/sim/road_profile.hpp"

namespace roadload::sim {

// IRI per ASTM E1926 (Sayers' quarter-car algorithm): the Golden Car, per unit sprung mass
// k1 = 653 s^-2 (tire), k2 = 63.3 s^-2 (suspension), mu = 0.15 (unsprung/sprung), c = 6.0 s^-1,
// at 80 km/h over the raw profile smoothed by a 250 mm moving average, started from the mean slope
// of the first 11 m. Result in m/km over the samples nearest [from_m, to_m]; NaN if that is shorter
// than the 250 mm base.
double iri_m_per_km(const RoadProfile& profile, double from_m, double to_m);

}  // namespace roadload::sim
