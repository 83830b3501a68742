// A coast-down in neutral is a force balance without the engine: no tractive force, so neither
// the ECU's torque nor its scale, bias or the driveline's efficiency enter the CRR it gives. The
// analyzer uses it (ETC2 current gear 0, clutch released), and its CRR stays put whatever torque
// scale the analysis holds, where a powered cruise's moves with it.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "roadload/drive_analyzer.hpp"
#include "sim_fixture.hpp"

namespace roadload::sim {
namespace {

struct Outcome {
  double crr = 0, crr_sigma = 0, truth = 0;
  double usable_share = 0;
};

// The drive analysed with the torque scale held at `held` (0: exact); the ECU reports its torque
// 5 % high.
Outcome analyse(const char* scenario, double held) {
  const j1939::Database db = test::core_database();
  Scenario sc = test::builtin(scenario);
  sc.effects.set(Effect::torque_bias, 0.05);
  const test::DriveWithTruth drive = test::drive_with_truth(sc, 4, db);
  auto route = RouteGeometry::build(sc.route.points);
  EXPECT_TRUE(route.has_value());
  AnalyzerConfig cfg = test::analyzer_config(sc);
  cfg.filter.truck.torque_scale_sigma = 0;
  cfg.filter.torque_scale_held = held;
  DriveAnalyzer analyzer(db, *route, test::cell_spans(sc), cfg);
  test::analyze(analyzer, drive.sink);
  Outcome o;
  double sum = 0, n = 0;
  for (const auto& c : drive.cells) {
    if (!c.complete) continue;
    sum += c.crr;
    ++n;
  }
  // A coast-down stops inside the flat track's one pavement, whose CRR the route states.
  o.truth = n > 0 ? sum / n : sc.route.default_crr;
  o.crr = analyzer.trip().crr;
  o.crr_sigma = analyzer.trip().crr_sigma;
  o.usable_share = static_cast<double>(analyzer.trip().usable_ticks) / static_cast<double>(analyzer.trip().ticks);
  return o;
}

TEST(CoastDownCrr, NeutralCoastingIsUsedAndItsCrrIgnoresTheTorque) {
  const Outcome exact = analyse("coast-down-65mph", 0.0);
  const Outcome scaled = analyse("coast-down-65mph", 0.05);
  std::printf(
      "coast-down, torque reported 5 %% high: CRR %.5f +- %.5f (truth %.5f), %.0f %% of ticks usable; "
      "held at +5 %%: %.5f\n",
      exact.crr, exact.crr_sigma, exact.truth, 100 * exact.usable_share, scaled.crr);
  EXPECT_GT(exact.usable_share, 0.9);
  EXPECT_NEAR(exact.crr, exact.truth, 3 * exact.crr_sigma);
  EXPECT_LT(exact.crr_sigma, 0.0008);
  EXPECT_NEAR(scaled.crr, exact.crr, 1e-6);
}

TEST(CoastDownCrr, APoweredCruisesCrrMovesWithTheHeldScale) {
  const Outcome exact = analyse("mnroad-mainline-30mph", 0.0);
  const Outcome scaled = analyse("mnroad-mainline-30mph", 0.05);
  std::printf("cruise at 30 mph, torque reported 5 %% high: CRR %.5f (truth %.5f); held at +5 %%: %.5f\n", exact.crr, exact.truth,
              scaled.crr);
  EXPECT_GT(std::abs(scaled.crr - exact.crr), 0.0003);
}

}  // namespace
}  // namespace roadload::sim
