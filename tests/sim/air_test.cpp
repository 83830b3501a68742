#include <gtest/gtest.h>

#include <cmath>

#include "roadload/sim/air.hpp"
#include "roadload/sim/random.hpp"

namespace roadload::sim {
namespace {

// docs/simulator-parameters.md check 8: the weather of Tables 5.2 and 5.4.
TEST(AirDensity, MatchesTheReportsWeatherDays) {
  EXPECT_NEAR(air_density_kgpm3(98100.0, 14.3), 1.189, 0.0005);
  EXPECT_NEAR(air_density_kgpm3(97680.0, 14.9), 1.181, 0.0005);
  EXPECT_NEAR(air_density_kgpm3(98130.0, 21.4), 1.161, 0.0005);
}

TEST(RelativeWind, HeadTailAndCrossWind) {
  // Heading west (270), wind from 270: pure head wind.
  auto w = relative_wind(20.0, 270.0, 5.0, 270.0);
  EXPECT_NEAR(w.airspeed_mps, 25.0, 1e-12);
  EXPECT_NEAR(w.yaw_rad, 0.0, 1e-12);
  w = relative_wind(20.0, 270.0, 5.0, 90.0);
  EXPECT_NEAR(w.airspeed_mps, 15.0, 1e-12);
  // 64 mph with a 4 m/s pure crosswind: 8.0 degrees of yaw (parameter sheet, Sect. 4).
  w = relative_wind(64 * 0.44704, 0.0, 4.0, 90.0);
  EXPECT_NEAR(std::abs(w.yaw_rad) * 180.0 / 3.141592653589793, 8.0, 0.05);
}

TEST(Rng, SameSeedSameSequenceAndStreamsDiffer) {
  Rng a(7, 1), b(7, 1), c(7, 2);
  for (int i = 0; i < 100; ++i) EXPECT_EQ(a.next_u64(), b.next_u64());
  EXPECT_NE(Rng(7, 1).next_u64(), c.next_u64());
}

TEST(Rng, NormalHasUnitVariance) {
  Rng r(42);
  double s = 0, s2 = 0;
  constexpr int n = 200000;
  for (int i = 0; i < n; ++i) {
    const double x = r.normal();
    s += x;
    s2 += x * x;
  }
  EXPECT_NEAR(s / n, 0.0, 0.01);
  EXPECT_NEAR(s2 / n, 1.0, 0.01);
}

}  // namespace
}  // namespace roadload::sim
