// The fuel breakdown on intervals computed by hand: each row is the work of one force, and the
// rows sum to the measured fuel exactly when the force balance closes.
#include "roadload/fuel_breakdown.hpp"

#include <gtest/gtest.h>

#include <numbers>

namespace roadload {
namespace {

constexpr double kOmega = 100.0;  // rad/s: keeps the hand sums round
constexpr double kRpm = kOmega * 60.0 / (2.0 * std::numbers::pi);
constexpr double kTolJ = 1e-6;

// Fuel whose energy is fuel_j over dt_s, as LFE1 would report it.
double rate_lph(double fuel_j, double dt_s) { return fuel_j / kDieselEnergy_jpl / dt_s * 3600.0; }

// 1 s at 20 m/s (20 m): indicated 1000 N m at 100 rad/s = 100 kJ at 40 % (250 kJ of fuel);
// friction 150 and parasitic 50 N m leave 80 kJ at the flywheel, 4 kJ of it lost in the driveline,
// 76 kJ = 3800 N x 20 m at the wheels against aero 1500 + rolling 2000 + grade 300 N.
PowerInterval steady() {
  PowerInterval p;
  p.dt_s = 1.0;
  p.fuel_rate_lph = rate_lph(250e3, 1.0);
  p.engine_speed_rpm = kRpm;
  p.indicated_nm = 1000, p.friction_nm = 150, p.parasitic_nm = 50;
  p.engaged = true;
  p.tractive_n = 3800;
  p.speed_from_mps = p.speed_to_mps = 20;
  p.effective_mass_kg = 40000;
  p.aero_n = 1500, p.rolling_n = 2000, p.grade_n = 300;
  return p;
}

TEST(FuelBreakdown, SteadyIntervalSplitsFuelIntoRowsThatSumExactly) {
  FuelBreakdown b;
  b.add(steady());
  EXPECT_NEAR(b.energy(FuelUse::engine), 250e3 - 100e3 + 15e3, kTolJ);  // not indicated, plus friction
  EXPECT_NEAR(b.energy(FuelUse::accessories), 5e3, kTolJ);
  EXPECT_NEAR(b.energy(FuelUse::driveline), 4e3, kTolJ);
  EXPECT_NEAR(b.energy(FuelUse::aero), 30e3, kTolJ);
  EXPECT_NEAR(b.energy(FuelUse::rolling), 40e3, kTolJ);
  EXPECT_NEAR(b.energy(FuelUse::grade), 6e3, kTolJ);
  EXPECT_NEAR(b.energy(FuelUse::acceleration), 0.0, kTolJ);
  EXPECT_NEAR(b.energy(FuelUse::braking), 0.0, kTolJ);
  EXPECT_NEAR(b.distance_m, 20.0, 1e-12);
  EXPECT_NEAR(b.sum_l(), b.fuel_l, 1e-15);
  EXPECT_NEAR(b.closure(), 0.0, 1e-12);
}

TEST(FuelBreakdown, LitresAreJoulesOverDieselEnergy) {
  FuelBreakdown b;
  b.add(steady());
  b.add(steady());
  EXPECT_NEAR(b.fuel_l, 2 * 250e3 / kDieselEnergy_jpl, 1e-15);
  EXPECT_NEAR(b.liters(FuelUse::rolling), 80e3 / 35.8e6, 1e-15);
  EXPECT_NEAR(b.liters(FuelUse::rolling, 40e6), 80e3 / 40e6, 1e-15);  // another fuel's energy content
  EXPECT_NEAR(b.sum_l(), 500e3 / 35.8e6, 1e-15);
  EXPECT_NEAR(b.distance_m, 40.0, 1e-12);
}

// Braking from 20 to 18 m/s in 1 s (19 m), flywheel torque zero, downhill: the brakes took the
// kinetic energy lost, 0.5 x 40 t x (400 - 324) = 1.52 MJ, less the resistances' 2500 N x 19 m.
TEST(FuelBreakdown, BrakingRowIsTheKineticEnergyTheResistancesDidNotTake) {
  PowerInterval p;
  p.dt_s = 1.0;
  p.fuel_rate_lph = rate_lph(50e3, 1.0);
  p.engine_speed_rpm = kRpm;
  p.indicated_nm = 200, p.friction_nm = 150, p.parasitic_nm = 50;
  p.engaged = true;
  p.braking = true;
  p.tractive_n = 0;
  p.speed_from_mps = 20, p.speed_to_mps = 18;
  p.effective_mass_kg = 40000;
  p.aero_n = 1000, p.rolling_n = 2000, p.grade_n = -500;
  FuelBreakdown b;
  b.add(p);
  EXPECT_NEAR(b.energy(FuelUse::acceleration), -1.52e6, kTolJ);
  EXPECT_NEAR(b.energy(FuelUse::braking), 1.52e6 - 2500.0 * 19.0, kTolJ);
  EXPECT_NEAR(b.energy(FuelUse::grade), -9.5e3, kTolJ);
  EXPECT_NEAR(b.energy(FuelUse::driveline), 0.0, kTolJ);
  EXPECT_NEAR(b.closure(), 0.0, 1e-12);  // the brake row closes the balance by construction
}

// Declutched for 0.5 s: the flywheel's 100 N m x 100 rad/s x 0.5 s = 5 kJ spins the engine, not the
// wheels, so it is the driveline row whatever tractive force a stale gear ratio gives; the truck
// coasts, 40 t slowing by 3800 N x 0.5 s / 40 t = 0.0475 m/s.
TEST(FuelBreakdown, DeclutchedFlywheelWorkIsDrivelineAndTractiveForceIsIgnored) {
  PowerInterval p = steady();
  p.dt_s = 0.5;
  p.fuel_rate_lph = rate_lph(37.5e3, 0.5);
  p.indicated_nm = 300;
  p.engaged = false;
  p.tractive_n = 9999;
  p.speed_to_mps = 20 - 0.0475;
  FuelBreakdown b;
  b.add(p);
  EXPECT_NEAR(b.energy(FuelUse::driveline), 5e3, kTolJ);
  EXPECT_NEAR(b.energy(FuelUse::engine), 37.5e3 - 15e3 + 7.5e3, kTolJ);
  EXPECT_NEAR(b.energy(FuelUse::accessories), 2.5e3, kTolJ);
  EXPECT_NEAR(b.energy(FuelUse::acceleration), -3800 * b.distance_m, 1e-6);
  EXPECT_NEAR(b.energy(FuelUse::braking), 0.0, kTolJ);
  EXPECT_NEAR(b.closure(), 0.0, 1e-9);
}

// From 10 to 10.2 m/s in 1 s (10.1 m) with 40 t effective: 0.5 x 40 t x (104.04 - 100) = 80.8 kJ,
// driven by 8000 N of tractive force beyond the resistances (8000 N x 10.1 m).
TEST(FuelBreakdown, AccelerationRowIsKineticEnergyGained) {
  PowerInterval p = steady();
  p.speed_from_mps = 10, p.speed_to_mps = 10.2;
  p.tractive_n = 3800 + 8000;
  p.indicated_nm = 150 + 50 + 11800 * 10.1 / kOmega;  // a lossless driveline
  p.fuel_rate_lph = rate_lph(p.indicated_nm * kOmega / 0.4, 1.0);
  FuelBreakdown b;
  b.add(p);
  EXPECT_NEAR(b.energy(FuelUse::acceleration), 80.8e3, kTolJ);
  EXPECT_NEAR(b.energy(FuelUse::driveline), 0.0, 1e-6);
  EXPECT_NEAR(b.energy(FuelUse::braking), 0.0, kTolJ);
  EXPECT_NEAR(b.closure(), 0.0, 1e-12);
}

// A force side that claims more than the wheels delivered (rolling 2200 N instead of 2000 N:
// 4 kJ too much of 250 kJ) shows as a positive closure, one that claims less as a negative one.
TEST(FuelBreakdown, ClosureIsPositiveWhenTheForceSideOverCounts) {
  PowerInterval over = steady(), under = steady();
  over.rolling_n = 2200;
  under.rolling_n = 1800;
  FuelBreakdown b_over, b_under;
  b_over.add(over);
  b_under.add(under);
  EXPECT_NEAR(b_over.closure(), 4e3 / 250e3, 1e-12);
  EXPECT_NEAR(b_under.closure(), -4e3 / 250e3, 1e-12);
}

TEST(FuelBreakdown, NoFuelMeansNoClosure) {
  FuelBreakdown b;
  EXPECT_EQ(b.closure(), 0.0);
  EXPECT_STREQ(to_string(FuelUse::rolling), "rolling");
  EXPECT_STREQ(to_string(FuelUse::braking), "braking");
}

TEST(FuelBreakdown, WithoutTheEngineTorquesTheWheelSideSplitsAndTheRestIsEngine) {
  FuelBreakdown b;
  b.add(steady());
  PowerInterval blind = steady();
  blind.attributable = false;
  b.add(blind);
  EXPECT_NEAR(b.fuel_l, 2 * 250e3 / kDieselEnergy_jpl, 1e-15);
  EXPECT_NEAR(b.unsplit_l, 250e3 / kDieselEnergy_jpl, 1e-15);
  EXPECT_NEAR(b.energy(FuelUse::aero), 60e3, kTolJ);        // the wheel side of both intervals
  EXPECT_NEAR(b.energy(FuelUse::accessories), 5e3, kTolJ);  // the engine side of the first only
  EXPECT_NEAR(b.energy(FuelUse::engine), 165e3 + 250e3 - 76e3, kTolJ);
  EXPECT_NEAR(b.closure(), 0.0, 1e-12);
  EXPECT_NEAR(b.distance_m, 40.0, 1e-12);
}

}  // namespace
}  // namespace roadload
