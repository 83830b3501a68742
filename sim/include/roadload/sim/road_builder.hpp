#pragma once
// The road a scenario drives: its route's cells turned into a profile. A cell's IRI is the IRI of
// the whole surface, so on jointed concrete the random part is lowered until random roughness plus
// joints give that IRI (docs/simulator-parameters.md 6.1).
#include "roadload/sim/road_profile.hpp"
#include "roadload/sim/route.hpp"
#include "roadload/sim/scenario.hpp"

namespace roadload::sim {

// Joint-only IRI of a segment's joints, computed on a 1 km stretch of them.
double joint_iri_m_per_km(const JointSpec& joints, std::uint64_t seed);

// Segments with G_d(n0) lowered where joints add roughness: IRI_random^2 = IRI_cell^2 - IRI_joints^2
// (IRIs of independent profiles add nearly in quadrature).
std::vector<ProfileSegment> hold_cell_iri(std::vector<ProfileSegment> segments, std::uint64_t seed);

// The profile a scenario drives on, from a little before the trailer's last axle to past the end.
RoadProfile build_road(const Scenario& scenario, const Route& route);

}  // namespace roadload::sim
