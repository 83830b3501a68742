// An accelerometer whose z lacks gravity is named; one mounted as the format says is not.
#include <gtest/gtest.h>

#include "roadload/gravity_check.hpp"

namespace roadload {
namespace {

AccelSample sample(std::uint8_t sensor, double z) {
  AccelSample s{};
  s.sensor = sensor;
  s.z_mps2 = z;
  return s;
}

TEST(GravityCheck, NamesASensorUpsideDownAndOneWithoutGravityButNotAnUprightOne) {
  GravityCheck g;
  for (int i = 0; i < 2000; ++i) {
    const double vibration = (i % 2 ? 1.5 : -1.5);
    g.push(sample(0, 9.81 + vibration));   // upright
    g.push(sample(1, -9.81 + vibration));  // upside down
    g.push(sample(2, vibration));          // gravity taken out
    g.push(sample(3, 9.81 * 0.995));       // upright on a 10 % grade
  }
  g.push(sample(4, 0.0));  // too few samples to judge
  const auto found = g.implausible();
  ASSERT_EQ(found.size(), 2u);
  EXPECT_EQ(found[0].sensor, 1);
  EXPECT_NEAR(found[0].mean_z_mps2, -9.81, 1e-9);
  EXPECT_EQ(found[0].samples, 2000u);
  EXPECT_EQ(found[1].sensor, 2);
  EXPECT_NEAR(found[1].mean_z_mps2, 0.0, 1e-9);
}

}  // namespace
}  // namespace roadload
