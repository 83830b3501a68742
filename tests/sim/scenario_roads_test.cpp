// The built-in roads are the report's roads: TH 10 and TH 66 profiles (random roughness plus
// joints) have the IRI of Chapter 5, the Mainline cells carry Table 6.3's CRR and Table 5.1's panels.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "roadload/sim/iri.hpp"
#include "roadload/sim/road_builder.hpp"
#include "sim_fixture.hpp"

namespace roadload::sim {
namespace {

double scenario_iri(const std::string& name) {
  const Scenario sc = test::builtin(name);
  auto route = Route::build(sc.route);
  EXPECT_TRUE(route.ok());
  const RoadProfile p = build_road(sc, route.value());
  const double iri = iri_m_per_km(p, sc.start_m, sc.end_m);
  std::printf("%s: IRI %.3f m/km over %.0f m\n", name.c_str(), iri, sc.end_m - sc.start_m);
  return iri;
}

TEST(ScenarioRoads, Th10ProfileWithJointsHasIri2p55) { EXPECT_NEAR(scenario_iri("th10-55mph"), 2.55, 0.05 * 2.55); }

TEST(ScenarioRoads, Th66ProfileHasIri2p65) { EXPECT_NEAR(scenario_iri("th66-55mph"), 2.65, 0.05 * 2.65); }

TEST(ScenarioRoads, JointsAreAccountedInTheCellIri) {
  JointSpec j;
  j.spacing_m = 8.5344;
  j.faulting_m = 0.004;
  const double joints = joint_iri_m_per_km(j, 3);
  EXPECT_GT(joints, 0.5);  // 4 mm faults every 28 ft are rough on their own
  const auto held = hold_cell_iri({{0, 1000, gd_from_iri_m3(2.55), j}}, 3);
  EXPECT_NEAR(iri_from_gd_m_per_km(held[0].gd_n0_m3), std::sqrt(2.55 * 2.55 - joints * joints), 1e-9);
}

TEST(ScenarioRoads, MainlineCellsFollowTables51And63) {
  const Scenario sc = test::builtin("mnroad-mainline-30mph");
  ASSERT_EQ(sc.route.cells.size(), 29u);
  EXPECT_EQ(sc.route.cells.front().id, "23");
  EXPECT_DOUBLE_EQ(sc.route.cells.front().crr, 0.0061);
  EXPECT_NEAR(sc.route.cells.front().start_m, 579.3, 1e-9);
  double sum = 0;
  for (const Cell& c : sc.route.cells) sum += c.crr;
  EXPECT_NEAR(sum / 29, 0.00557, 0.000005);  // the 29 rows' mean
  const auto find = [&](const char* id) {
    return *std::find_if(sc.route.cells.begin(), sc.route.cells.end(), [&](const Cell& c) { return c.id == id; });
  };
  EXPECT_EQ(find("306").crr, 0.0072);
  EXPECT_EQ(find("4").crr, 0.0044);
  EXPECT_EQ(find("73").surface, "concrete");
  EXPECT_NEAR(find("73").joint_spacing_m, 15 * 0.3048, 1e-4);
  EXPECT_NEAR(find("96").joint_spacing_m, 5 * 0.3048, 1e-4);
  EXPECT_NEAR(find("7").joint_spacing_m, 20 * 0.3048, 1e-4);
  EXPECT_EQ(find("22").surface, "bituminous");
  EXPECT_NEAR(sc.speed_mps, 13.4112, 1e-9);
  EXPECT_NEAR(sc.weather.air_temp_c, 14.3, 1e-9);
}

}  // namespace
}  // namespace roadload::sim
