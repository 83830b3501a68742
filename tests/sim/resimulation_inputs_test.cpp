// What a re-simulation of a recorded drive sets in the plant (roadload gap): the measured wind as a
// time series instead of a drawn wander, and the recorded mass as a load scale.
#include <gtest/gtest.h>

#include <cmath>

#include "roadload/sim/truck.hpp"
#include "roadload/sim/wind.hpp"
#include "sim_fixture.hpp"

namespace roadload::sim {
namespace {

TEST(WindTrace, IsTheMeanWindInterpolatedInTimeWithNoWander) {
  WeatherSpec w;
  w.wander_mps = 1.0;  // would move the wind by metres per second over the run if it were drawn
  w.wind_trace = {{10.0, 2.0, 0.0}, {20.0, 0.0, -3.0}};
  WindField field(w, 0.0, Rng(3));
  // Before the trace: its first point. Wind blowing east comes from the west.
  Environment e = field.at_truck();
  EXPECT_NEAR(e.wind_speed_mps, 2.0, 1e-12);
  EXPECT_NEAR(e.wind_from_deg, 270.0, 1e-9);
  for (int i = 0; i < 15000; ++i) field.advance(0.001);  // t = 15 s: halfway
  e = field.at_truck();
  EXPECT_NEAR(e.wind_speed_mps, std::hypot(1.0, 1.5), 1e-9);
  for (int i = 0; i < 15000; ++i) field.advance(0.001);  // t = 30 s: past the end
  e = field.at_truck();
  EXPECT_NEAR(e.wind_speed_mps, 3.0, 1e-12);
  EXPECT_NEAR(e.wind_from_deg, 0.0, 1e-9);                  // blowing south: from the north
  EXPECT_NEAR(field.at_mast().wind_speed_mps, 3.0, 1e-12);  // the mast measured it
}

TEST(LoadScale, ScalesEveryAxlesLoadThroughItsSprungMass) {
  Scenario s = test::builtin("mnroad-mainline-30mph");
  s.load_scale = 1.1;
  const j1939::Database db = test::core_database();
  Simulation heavier(s, 1, db);
  const TruckParams nominal = truck_from_vehicle(s.vehicle, s.unsprung);
  const TruckParams& t = heavier.plant().truck();
  EXPECT_NEAR(t.total_mass_kg(), 1.1 * nominal.total_mass_kg(), 1e-6);
  for (std::size_t a = 0; a < t.axles.size(); ++a) {
    EXPECT_DOUBLE_EQ(t.axles[a].vertical.unsprung_kg, nominal.axles[a].vertical.unsprung_kg);
    EXPECT_NEAR(t.axles[a].vertical.sprung_kg + t.axles[a].vertical.unsprung_kg, t.axles[a].load_kg, 1e-9);
  }
  EXPECT_NEAR(heavier.metadata().vehicle.at("mass_kg"), 1.1 * nominal.total_mass_kg(), 1e-6);
}

}  // namespace
}  // namespace roadload::sim
