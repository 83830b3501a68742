// City traffic in the simulator: before every stop line the truck brakes to a crawl and then
// climbs back through the gears to its set speed, block after block.
#include <gtest/gtest.h>

#include "sim_fixture.hpp"

namespace roadload::sim {
namespace {

constexpr double kMph = 0.44704;

TEST(StopAndGo, BrakesToACrawlAtEveryStopLineAndComesBackToTheSetSpeed) {
  Scenario sc = test::builtin("mnroad-mainline-30mph");
  sc.speed_mps = 25 * kMph;
  sc.stops = {500.0, 3 * kMph, 60.0};
  sc.end_m = sc.start_m + 1495.0;  // three blocks, the run ending in the third crawl
  const test::MemorySink drive = test::drive_without_accelerometers(sc, 5, test::core_database());
  ASSERT_FALSE(drive.fixes.empty());
  int crawls = 0, recoveries = 0;
  bool at_speed = true;  // the run starts at the set speed
  for (const GnssFix& f : drive.fixes) {
    if (at_speed && f.speed_mps < 2.5) {
      ++crawls;
      at_speed = false;
    } else if (!at_speed && f.speed_mps > 0.9 * sc.speed_mps) {
      ++recoveries;
      at_speed = true;
    }
  }
  EXPECT_EQ(crawls, 3);
  EXPECT_EQ(recoveries, 2);
}

}  // namespace
}  // namespace roadload::sim
