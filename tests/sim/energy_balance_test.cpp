// Fuel energy in equals the work of every force plus every loss, over a whole trip.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "roadload/sim/units.hpp"
#include "sim_fixture.hpp"
#include "vehicles.hpp"

namespace roadload::sim {
namespace {

class EnergyBalance : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    Scenario s = test::builtin("mnroad-mainline-30mph");
    s.duration = Seconds{120.0};
    // Effects that move energy between terms: fan, driveline losses, friction in the leaf spring.
    s.effects.set(Effect::fan_engagement, 0.3);
    s.effects.set(Effect::driveline_losses, 1.0);
    s.effects.set(Effect::suspension_friction, 1500.0);
    s.effects.set(Effect::wind_gusts, 1.5);
    db_ = new j1939::Database(test::core_database());
    sim_ = new Simulation(s, 3, *db_);
    test::MemorySink sink;
    summary_ = sim_->run(sink, nullptr);
  }
  static void TearDownTestSuite() {
    delete sim_;
    delete db_;
  }
  static inline j1939::Database* db_ = nullptr;
  static inline Simulation* sim_ = nullptr;
  static inline RunSummary summary_;
};

TEST_F(EnergyBalance, FuelEnergyEqualsEveryWorkAndLossWithinOnePerMille) {
  const EnergyLedger& e = summary_.ledger;
  const double out = e.thermal_j + e.friction_j + e.accessories_j + e.fan_j + e.driveline_j + e.roll_j + e.aero_j + e.grade_j +
                     e.profile_j + e.brake_j + e.kinetic_j + e.clutch_j;
  ASSERT_GT(e.fuel_j, 1e7);
  std::printf("fuel %.6g J, sum of works and losses %.6g J, ratio %.9f\n", e.fuel_j, out, out / e.fuel_j);
  EXPECT_NEAR(out / e.fuel_j, 1.0, 1e-3);
  // Every term is there and of a plausible sign and share.
  EXPECT_GT(e.thermal_j / e.fuel_j, 0.5);
  EXPECT_GT(e.roll_j, 0.0);
  EXPECT_GT(e.aero_j, 0.0);
  EXPECT_GT(e.fan_j, 0.0);
  EXPECT_GT(e.driveline_j, 0.0);
  EXPECT_GT(e.profile_j, 0.0);
}

TEST_F(EnergyBalance, RollingWorkIsCrrTimesWeightTimesDistance) {
  // CRR 0.0048-0.0063 over the cells of the first 120 s: the work lies in that band.
  const double weight_n = sim_->plant().truck().total_mass_kg() * kGravity_mps2;
  const double crr = summary_.ledger.roll_j / (weight_n * summary_.ledger.distance_m);
  EXPECT_GT(crr, 0.0048);
  EXPECT_LT(crr, 0.0063);
}

TEST_F(EnergyBalance, ProfileWorkFeedsTheSuspensionsAndTires) {
  // The horizontal share of the tire forces on the profile is the energy the dampers, tires and
  // friction dissipate, plus what is stored and the weight lifted over the profile.
  const AxleEnergy v = sim_->plant().vertical_energy();
  const double dissipated = v.damper_j + v.tire_j + v.friction_j;
  ASSERT_GT(dissipated, 0.0);
  EXPECT_NEAR(v.road_work_j, dissipated + sim_->plant().vertical_stored_energy_j(), 0.01 * dissipated);
  // The longitudinal side sees the same energy, up to the static weight times the net profile rise.
  const double profile = summary_.ledger.profile_j;
  std::printf("profile work %.1f J, vertical road work %.1f J, dissipated %.1f J\n", profile, v.road_work_j, dissipated);
  EXPECT_NEAR(profile / v.road_work_j, 1.0, 0.1) << "profile " << profile << " J, road work " << v.road_work_j << " J";
}

}  // namespace
}  // namespace roadload::sim

namespace roadload::sim {
namespace {

TEST(EnergyBalanceWithShifts, AcceleratingThroughAGearChangeStillCloses) {
  const Scenario sc = test::builtin("coast-down-65mph");  // the flat track
  auto route = Route::build(sc.route);
  ASSERT_TRUE(route.ok());
  const auto segs = route.value().profile_segments(0, 8000, 0, 0);
  const RoadProfile profile = RoadProfile::generate(segs, 0, 8000, 1);
  TruckPlant plant(truck_from_vehicle(roadload::shipped::mnroad_vehicle()), route.value(), profile, EffectSet{}, 1);
  Environment air;
  plant.start(50, 40 * 0.44704, air);
  const int first_gear = plant.state().gear;
  plant.set_cruise_speed(64 * 0.44704);
  int shifts = 0, gear = first_gear;
  for (int k = 0; k < 240 * 1000 && plant.state().x_m < 7900; ++k) {
    plant.step(0.001, air);
    if (plant.state().gear != 0 && plant.state().gear != gear) {
      ++shifts;
      gear = plant.state().gear;
    }
  }
  EXPECT_GE(shifts, 1) << "from gear " << first_gear;
  EXPECT_GT(plant.state().speed_mps, 60 * 0.44704);
  const EnergyLedger& e = plant.ledger();
  const double out = e.thermal_j + e.friction_j + e.accessories_j + e.fan_j + e.driveline_j + e.roll_j + e.aero_j + e.grade_j +
                     e.profile_j + e.brake_j + e.kinetic_j + e.clutch_j;
  std::printf("accelerating 40->64 mph: %d shifts, fuel %.6g J, works and losses %.6g J, clutch %.1f J\n", shifts, e.fuel_j, out,
              e.clutch_j);
  EXPECT_NEAR(out / e.fuel_j, 1.0, 1e-3);
}

}  // namespace
}  // namespace roadload::sim
