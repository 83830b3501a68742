// A truck identified from its own drive: the simulated tractor, whose drive tires and gearbox are
// not quite its vehicle file's, driven on the Mainline; what the bus and the GNSS tell comes back
// within the acceptance's bounds (ratios 0.5 %, radius 0.3 %), and what they cannot tell is said.
#include "roadload/vehicle_identification.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "roadload/vehicle_file.hpp"
#include "sim_fixture.hpp"

namespace roadload::sim {
namespace {

Vehicle tractor() {
  auto v = load_vehicle_file(ROADLOAD_CONFIG_DIR "/vehicles/tractor-53ft-18speed.toml");
  EXPECT_TRUE(v.ok()) << (v.ok() ? "" : v.error().to_string());
  return v.value();
}

TEST(VehicleIdentification, TheTractorsGearsAndTiresComeBackFromItsDrive) {
  const j1939::Database db = test::core_database();
  const Vehicle prior = tractor();
  Scenario sc = test::builtin("mnroad-mainline-30mph");
  sc.vehicle = prior;
  // This truck: worn drive tires 1.2 % smaller, a gearbox whose ratios are 0.8 % taller.
  for (VehicleAxle& a : sc.vehicle.axles) {
    if (a.driven) a.tire_radius_m *= 0.988;
  }
  for (double& g : sc.vehicle.driveline.gear_ratios) g *= 1.008;
  sc.duration = Seconds{150};
  const test::MemorySink drive = test::drive_without_accelerometers(sc, 5, db);

  VehicleIdentifier id(db, prior);
  std::size_t f = 0, g = 0;
  while (f < drive.frames.size() || g < drive.fixes.size()) {
    if (g == drive.fixes.size() || (f < drive.frames.size() && drive.frames[f].t <= drive.fixes[g].t)) {
      id.push(drive.frames[f++]);
    } else {
      id.push(drive.fixes[g++]);
    }
  }
  const VehicleIdentification r = id.result();

  ASSERT_TRUE(r.reference_torque_nm);
  EXPECT_DOUBLE_EQ(r.reference_torque_nm->value, prior.engine.reference_torque_nm);
  std::size_t seen = 0;
  for (std::size_t k = 0; k < r.gear_ratios.size(); ++k) {
    if (!r.gear_ratios[k]) continue;
    ++seen;
    const double truth = sc.vehicle.driveline.gear_ratios[k];
    std::printf("gear %zu: identified %.4f +- %.4f, truth %.4f, prior %.4f\n", k + 1, r.gear_ratios[k]->value,
                r.gear_ratios[k]->sigma, truth, prior.driveline.gear_ratios[k]);
    EXPECT_NEAR(r.gear_ratios[k]->value / truth, 1.0, 0.005) << "gear " << k + 1 << " from " << r.gear_ratios[k]->source;
    EXPECT_LT(std::abs(r.gear_ratios[k]->value - truth), 3 * r.gear_ratios[k]->sigma + 0.001) << "gear " << k + 1;
  }
  EXPECT_GE(seen, 1u);
  ASSERT_TRUE(r.drive_tire_radius_m);
  const double radius = sc.vehicle.drive_axle()->tire_radius_m;
  std::printf("drive tire radius: identified %.5f +- %.5f m, truth %.5f, prior %.5f\n", r.drive_tire_radius_m->value,
              r.drive_tire_radius_m->sigma, radius, prior.drive_axle()->tire_radius_m);
  EXPECT_NEAR(r.drive_tire_radius_m->value / radius, 1.0, 0.003);
  EXPECT_LT(std::abs(r.drive_tire_radius_m->value - radius), 3 * r.drive_tire_radius_m->sigma + 1e-4);
  // The simulated bus sends neither VI nor CVW: both are said, not guessed.
  EXPECT_TRUE(r.vin.empty());
  EXPECT_FALSE(r.mass_kg);
  const auto said = [&](const char* what) {
    return std::any_of(r.not_identified.begin(), r.not_identified.end(), [&](const std::string& s) { return s.rfind(what, 0) == 0; });
  };
  EXPECT_TRUE(said("vin:"));
  EXPECT_TRUE(said("mass:"));
  EXPECT_TRUE(said("driveline.gear_ratios:"));  // an 18-speed box is not driven through on one road
}

}  // namespace
}  // namespace roadload::sim
