// Accelerometers onto the common grid: the anti-alias filter, interpolation across the parts' own
// clocks, gaps, and the velocity integrator whose response is divided out of the densities.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

#include "allocation_counter.hpp"
#include "roadload/spectra/sensor_grid.hpp"

namespace roadload::spectra {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

AccelSample sample(std::uint8_t id, double t_s, double z) {
  AccelSample s;
  s.t = capture_time_from_ns(std::llround(t_s * 1e9));
  s.sensor = id;
  s.z_mps2 = z;
  return s;
}

// Two parts 0.7 % apart in rate, sampling the same 3 Hz motion: on the grid they agree.
TEST(SensorGrid, TwoClocksLandOnTheSameInstants) {
  const GridSensor parts[] = {{1, 1200.0}, {2, 1200.0}};
  SensorGrid grid(parts);
  const auto motion = [](double t) { return 9.81 + 0.5 * std::sin(kTwoPi * 3.0 * t); };
  double ta = 10.0, tb = 10.0003;
  while (ta < 30.0 || tb < 30.0) {
    if (ta <= tb) {
      grid.push(sample(1, ta, motion(ta)));
      ta += 1.0 / 1200.0;
    } else {
      grid.push(sample(2, tb, motion(tb)));
      tb += 1.0 / 1191.6;
    }
  }
  std::vector<double> a(400), b(400);
  const std::int64_t end = grid.latest() - 10;
  ASSERT_TRUE(grid.copy(0, end, a));
  ASSERT_TRUE(grid.copy(1, end, b));
  double worst = 0;
  for (std::size_t i = 0; i < a.size(); ++i) worst = std::max(worst, std::abs(a[i] - b[i]));
  EXPECT_LT(worst, 1e-3);  // 0.2 % of the motion: linear interpolation at 1.2 kHz
}

TEST(SensorGrid, AGapLeavesHolesAndRestartsAfterAWarmUp) {
  const GridSensor parts[] = {{1, 1000.0}};
  SensorGrid grid(parts);
  for (double t = 1.0; t < 13.0; t += 0.001) grid.push(sample(1, t, 9.81));
  for (double t = 13.5; t < 26.0; t += 0.001) grid.push(sample(1, t, 9.81));
  EXPECT_EQ(grid.restarts(), 1u);
  std::vector<double> seg(200);
  EXPECT_TRUE(grid.copy(0, static_cast<std::int64_t>(12.5 * 200), seg));
  EXPECT_FALSE(grid.copy(0, static_cast<std::int64_t>(13.3 * 200), seg));  // spans the gap
  EXPECT_FALSE(grid.copy(0, static_cast<std::int64_t>(20.0 * 200), seg));  // warming up again
  EXPECT_TRUE(grid.copy(0, static_cast<std::int64_t>(25.0 * 200), seg));
}

TEST(SensorGrid, VelocityOfASineIsItsAmplitudeOverOmega) {
  const GridSensor parts[] = {{1, 1200.0}};
  SensorGrid grid(parts);
  const double f = 5.0, amp = 1.0;
  for (int i = 0; i < 1200 * 30; ++i) {
    const double t = 1.0 + i / 1200.0;
    grid.push(sample(1, t, 9.81 + amp * std::sin(kTwoPi * f * t)));
  }
  std::vector<double> v(2000);
  ASSERT_TRUE(grid.copy_velocity(0, grid.latest() - 5, v));
  double peak = 0;
  for (double x : v) peak = std::max(peak, std::abs(x));
  const double expected = amp / (kTwoPi * f) * std::sqrt(grid.velocity_response_ratio(f));
  EXPECT_NEAR(peak, expected, 0.01 * expected);
  EXPECT_NEAR(grid.velocity_response_ratio(f), 1.0, 0.01);
  EXPECT_NEAR(grid.velocity_response_ratio(0.5), 1.0, 0.05);
}

TEST(SensorGrid, PushDoesNotAllocate) {
  const GridSensor parts[] = {{1, 1200.0}, {2, 800.0}};
  SensorGrid grid(parts);
  std::size_t allocations = 0;
  {
    test::CountAllocations count;
    for (int i = 0; i < 24000; ++i) grid.push(sample(static_cast<std::uint8_t>(1 + i % 2), 1.0 + i / 2400.0, 9.81));
    allocations = count.count();
  }
  EXPECT_EQ(allocations, 0u);
}

}  // namespace
}  // namespace roadload::spectra
