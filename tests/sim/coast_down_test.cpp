// A neutral coast-down from 65 mph on a flat smooth road in still air against the analytic
// solution of m dv/dt = -(A + C v^2) (docs/simulator-parameters.md, "Checks", 1).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "roadload/sim/air.hpp"
#include "roadload/sim/plant.hpp"
#include "roadload/sim/units.hpp"
#include "sim_fixture.hpp"
#include "vehicles.hpp"

namespace roadload::sim {
namespace {

TEST(CoastDown, From65MphMatchesTheAnalyticSolution) {
  const Scenario sc = test::builtin("coast-down-65mph");
  auto route = Route::build(sc.route);
  ASSERT_TRUE(route.ok());
  const std::vector<ProfileSegment> segs = route.value().profile_segments(0, 8000, 0, 0);
  const RoadProfile profile = RoadProfile::generate(segs, 0, 8000, sc.road_seed);
  const TruckParams truck = truck_from_vehicle(roadload::shipped::mnroad_vehicle());
  TruckPlant plant(truck, route.value(), profile, EffectSet{}, 1);
  Environment air;
  air.air_temp_c = sc.weather.air_temp_c;
  air.pressure_pa = sc.weather.pressure_pa;
  plant.set_coasting(true);
  const double v0 = 65 * kMps_per_mph, v_end = 30 * kMps_per_mph;
  plant.start(50, v0, air);

  const double m_eff = plant.effective_mass_kg();
  const double a = 0.0055 * truck.total_mass_kg() * kGravity_mps2;
  const double c = 0.5 * air_density_kgpm3(air.pressure_pa, air.air_temp_c) * truck.cda_m2;
  const double theta0 = std::atan(v0 * std::sqrt(c / a));
  const double theta_end = std::atan(v_end * std::sqrt(c / a));
  const double t_analytic = m_eff * (theta0 - theta_end) / std::sqrt(a * c);
  const double x_analytic = m_eff / c * std::log(std::cos(theta_end) / std::cos(theta0));
  // The parameter sheet's hand figures for this truck: 163.5 s over 3,331 m.
  EXPECT_NEAR(t_analytic, 163.5, 0.5);
  EXPECT_NEAR(x_analytic, 3331.0, 5.0);

  constexpr double dt = 1.0 / 1000.0;
  double t_prev = 0, v_prev = v0, x_prev = 50;
  while (plant.state().speed_mps > v_end) {
    t_prev = plant.state().t_s;
    v_prev = plant.state().speed_mps;
    x_prev = plant.state().x_m;
    plant.step(dt, air);
  }
  // Interpolate the crossing of 30 mph inside the last step.
  const double w = (v_prev - v_end) / (v_prev - plant.state().speed_mps);
  const double t_sim = t_prev + w * dt;
  const double x_sim = x_prev + w * (plant.state().x_m - x_prev) - 50;
  std::printf("coast-down 65->30 mph: simulated %.2f s over %.1f m, analytic %.2f s over %.1f m\n", t_sim, x_sim, t_analytic,
              x_analytic);
  EXPECT_NEAR(t_sim / t_analytic, 1.0, 1e-3) << "simulated " << t_sim << " s, analytic " << t_analytic << " s";
  EXPECT_NEAR(x_sim / x_analytic, 1.0, 1e-3) << "simulated " << x_sim << " m, analytic " << x_analytic << " m";
}

}  // namespace
}  // namespace roadload::sim
