// The analyzer's fuel breakdown from J1939 on the simulator's drives, against the plant's energy
// ledger (breakdown_truth): the measured fuel, the closure, cells against the trip, row by row.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>

#include "roadload/drive_analyzer.hpp"
#include "sim_fixture.hpp"

namespace roadload::sim {
namespace {

// Keeps the drive and, at every frame, integrates the energy J1939's whole-percent EEC3 rounding
// moves: the plant's true friction and accessory torque against what a whole percent of the
// reference torque says, times engine speed, over the plant's time since the previous frame.
class RoundingSink final : public SampleSink {
 public:
  explicit RoundingSink(const Simulation& sim) : sim_(sim) {}
  void frame(const CanFrame& f) override {
    const TruckState& s = sim_.plant().state();
    const double ref = sim_.plant().truck().engine.reference_torque_nm;
    const double omega_dt = s.engine_rpm * 2.0 * std::numbers::pi / 60.0 * (s.t_s - last_t_s_);
    const auto rounding_nm = [ref](double nm) { return std::nearbyint(nm / ref * 100.0) / 100.0 * ref - nm; };
    accessories_j += rounding_nm(s.accessory_torque_nm) * omega_dt;
    friction_j += rounding_nm(s.friction_torque_nm) * omega_dt;
    last_t_s_ = s.t_s;
    drive.frame(f);
  }
  void accel(const AccelSample& s) override { drive.accel(s); }
  void gnss(const GnssFix& s) override { drive.gnss(s); }
  void weather(const WeatherSample& s) override { drive.weather(s); }

  test::MemorySink drive;
  double accessories_j = 0, friction_j = 0;

 private:
  const Simulation& sim_;
  double last_t_s_ = 0;
};

struct Outcome {
  FuelBreakdown trip, cells;  // cells: the sum over every cell
  std::array<BreakdownTruth, 8> truth{};
  double plant_fuel_l = 0, fuel_j = 0;
  double rounding_accessories_j = 0, rounding_friction_j = 0;
  double driveline_efficiency = 0;
};

Outcome drive(const char* scenario) {
  const j1939::Database db = test::core_database();
  Scenario sc = test::builtin(scenario);
  sc.accelerometers = 0;  // the breakdown needs none; the run is faster without them
  Simulation sim(sc, 1, db);
  RoundingSink sink(sim);
  sim.run(sink, nullptr);
  auto route = RouteGeometry::build(sc.route.points);
  EXPECT_TRUE(route.has_value());
  DriveAnalyzer analyzer(db, *route, test::cell_spans(sc), test::analyzer_config(sc));
  test::analyze(analyzer, sink.drive);

  Outcome o;
  o.trip = analyzer.trip().fuel;
  for (const CellResult& c : analyzer.cells()) {
    o.cells.fuel_l += c.fuel.fuel_l;
    o.cells.distance_m += c.fuel.distance_m;
    for (std::size_t i = 0; i < kFuelUseCount; ++i) o.cells.energy_j[i] += c.fuel.energy_j[i];
  }
  const EnergyLedger& led = sim.plant().ledger();
  const FuelSpec& fuel = sim.plant().truck().fuel;
  o.truth = breakdown_truth(led);
  o.fuel_j = led.fuel_j;
  o.plant_fuel_l = led.fuel_j / (fuel.lhv_jpkg * fuel.density_kgpl);
  o.rounding_accessories_j = sink.accessories_j;
  o.rounding_friction_j = sink.friction_j;
  o.driveline_efficiency = sim.plant().truck().driveline.efficiency;
  return o;
}

// Relative error of a row; rows smaller than 1 % of the fuel energy (grade on a flat road,
// acceleration, braking) against 1 % of it, where a relative error says nothing.
double row_error(const Outcome& o, FuelUse u, double truth_j) {
  return (o.trip.energy(u) - truth_j) / std::max(std::abs(truth_j), 0.01 * o.fuel_j);
}

void check(const char* scenario) {
  const Outcome o = drive(scenario);
  const double fuel_err = o.trip.fuel_l / o.plant_fuel_l - 1.0;
  std::printf("%s: fuel %.4f L measured, %.4f L plant (%+.2f %%), closure %+.2f %%\n", scenario, o.trip.fuel_l, o.plant_fuel_l,
              100 * fuel_err, 100 * o.trip.closure());
  EXPECT_LT(std::abs(fuel_err), 0.01);
  EXPECT_LT(std::abs(o.trip.closure()), 0.01);

  // Cells never overlap, so what the cells miss is the fuel of the ticks outside any cell; at
  // cruise that is their share of the distance, and no row misses more than that share of the fuel.
  const double outside = 1.0 - o.cells.distance_m / o.trip.distance_m;
  const double fuel_outside = 1.0 - o.cells.fuel_l / o.trip.fuel_l;
  std::printf("  outside any cell: %.2f %% of the distance, %.2f %% of the fuel\n", 100 * outside, 100 * fuel_outside);
  EXPECT_GE(outside, 0.0);
  EXPECT_NEAR(fuel_outside, outside, 0.01);
  for (std::size_t i = 0; i < kFuelUseCount; ++i) {
    const double missed = o.trip.energy_j[i] - o.cells.energy_j[i];
    EXPECT_LE(std::abs(missed), (outside + 0.01) * o.trip.fuel_l * kDieselEnergy_jpl) << to_string(static_cast<FuelUse>(i));
  }

  // EEC3's whole percent moves energy from the flywheel to the accessories (and the engine
  // row): the flywheel work the estimator sees falls by as much, and the filter puts the wheels'
  // share of it, the driveline efficiency, into rolling resistance.
  const double moved_j = o.rounding_accessories_j + o.rounding_friction_j;
  std::array<double, kFuelUseCount> explained{};
  for (std::size_t i = 0; i < kFuelUseCount; ++i) explained[i] = o.truth[i].energy_j;
  explained[static_cast<std::size_t>(FuelUse::accessories)] += o.rounding_accessories_j;
  explained[static_cast<std::size_t>(FuelUse::engine)] += o.rounding_friction_j;
  explained[static_cast<std::size_t>(FuelUse::rolling)] -= o.driveline_efficiency * moved_j;
  explained[static_cast<std::size_t>(FuelUse::driveline)] -= (1 - o.driveline_efficiency) * moved_j;
  std::printf("  EEC3 rounding: accessories %+.1f kJ, friction %+.1f kJ\n", o.rounding_accessories_j / 1e3,
              o.rounding_friction_j / 1e3);
  std::printf("  %-13s %12s %12s %8s %12s %8s %10s\n", "row", "estimate kJ", "truth kJ", "error", "+rounding kJ", "error",
              "cells kJ");
  for (std::size_t i = 0; i < kFuelUseCount; ++i) {
    const auto u = static_cast<FuelUse>(i);
    std::printf("  %-13s %12.1f %12.1f %+7.2f%% %12.1f %+7.2f%% %10.1f\n", to_string(u), o.trip.energy(u) / 1e3,
                o.truth[i].energy_j / 1e3, 100 * row_error(o, u, o.truth[i].energy_j), explained[i] / 1e3,
                100 * row_error(o, u, explained[i]), o.cells.energy_j[i] / 1e3);
    // Once the rounding is accounted for, every row meets 5 %.
    EXPECT_LT(std::abs(row_error(o, u, explained[i])), 0.05) << to_string(u) << " with EEC3 rounding";
  }
  // These rows owe nothing to the rounding (or, the engine, too little to matter) and meet 5 % as
  // they are. The others do not: on the Mainline accessories +25.6 % (about 1.6 % of 2386 N m is sent
  // as 2 %), rolling -6.5 %, driveline -5.3 %.
  EXPECT_LT(std::abs(row_error(o, FuelUse::aero, o.truth[3].energy_j)), 0.05);
  EXPECT_LT(std::abs(row_error(o, FuelUse::grade, o.truth[5].energy_j)), 0.05);
  EXPECT_LT(std::abs(row_error(o, FuelUse::engine, o.truth[0].energy_j)), 0.05);
}

TEST(FuelBreakdownFromSimulation, MainlineAt30MphMatchesThePlantsLedger) { check("mnroad-mainline-30mph"); }

TEST(FuelBreakdownFromSimulation, Th66At55MphMatchesThePlantsLedger) { check("th66-55mph"); }

}  // namespace
}  // namespace roadload::sim
