#include "roadload/sim/road_builder.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "roadload/sim/iri.hpp"

namespace roadload::sim {
namespace {

constexpr double kRunIn_m = 40.0;  // beyond the truck's length (17.7 m) at both ends
constexpr double kTruckLength_m = 20.0;

}  // namespace

double joint_iri_m_per_km(const JointSpec& joints, std::uint64_t seed) {
  const ProfileSegment seg{0.0, 1000.0, 0.0, joints};
  const RoadProfile p = RoadProfile::generate(std::span(&seg, 1), 0.0, 1000.0, seed);
  return iri_m_per_km(p, 0.0, 1000.0);
}

std::vector<ProfileSegment> hold_cell_iri(std::vector<ProfileSegment> segments, std::uint64_t seed) {
  // Cells of one route share joint geometry: compute each distinct one once.
  std::map<std::array<double, 3>, double> cache;
  for (ProfileSegment& s : segments) {
    if (s.joints.spacing_m <= 0 || s.gd_n0_m3 <= 0) continue;
    const std::array<double, 3> key{s.joints.spacing_m, s.joints.faulting_m, s.joints.curl_m};
    auto it = cache.find(key);
    if (it == cache.end()) it = cache.emplace(key, joint_iri_m_per_km(s.joints, seed)).first;
    const double target = iri_from_gd_m_per_km(s.gd_n0_m3);
    // Joints alone rougher than the cell's IRI: keep a trace of random roughness, report as built.
    const double random = std::sqrt(std::max(target * target - it->second * it->second, 0.01 * target * target));
    s.gd_n0_m3 = gd_from_iri_m3(random);
  }
  return segments;
}

RoadProfile build_road(const Scenario& sc, const Route& route) {
  const double from = sc.start_m - kTruckLength_m - kRunIn_m;
  const double to = sc.end_m + kRunIn_m;
  auto segments = route.profile_segments(from, to, sc.effects.magnitude(Effect::joint_faulting),
                                         sc.effects.magnitude(Effect::slab_curl));
  return RoadProfile::generate(hold_cell_iri(std::move(segments), sc.road_seed), from, to, sc.road_seed);
}

}  // namespace roadload::sim
