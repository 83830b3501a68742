// Each sensor's clock is the scenario's to set: offsets and latencies move the stamps and nothing
// else, so a test of the daemon's alignment can inject them and know the answer.
#include <gtest/gtest.h>

#include "sim_fixture.hpp"

namespace roadload::sim {
namespace {

test::MemorySink run(const ClockSpec& clocks) {
  static const j1939::Database db = test::core_database();
  Scenario sc = test::builtin("th66-55mph");
  sc.duration = Seconds{3.0};
  sc.accelerometers = 2;
  sc.clocks = clocks;
  Simulation sim(sc, 4, db);
  test::MemorySink sink;
  sim.run(sink, nullptr);
  return sink;
}

TEST(SensorClocks, OffsetsAndLatenciesShiftOnlyTheStamps) {
  const test::MemorySink base = run(ClockSpec{});
  ClockSpec shifted;
  shifted.accel_offset = Seconds{0.25};
  shifted.accel_drift_ppm = 100;
  shifted.gnss_latency = Seconds{0.08};
  shifted.can_rx_latency = Seconds{0.001};
  shifted.weather_offset = Seconds{-0.5};
  const test::MemorySink moved = run(shifted);

  ASSERT_EQ(base.accels.size(), moved.accels.size());
  for (std::size_t i = 0; i < base.accels.size(); i += 997) {
    const double t = to_seconds(base.accels[i].t.time_since_epoch());
    EXPECT_NEAR(to_seconds(moved.accels[i].t - base.accels[i].t), 0.25 + 100e-6 * t, 2e-9);
    EXPECT_EQ(moved.accels[i].z_mps2, base.accels[i].z_mps2);  // the same sample, stamped later
  }
  ASSERT_EQ(base.fixes.size(), moved.fixes.size());
  EXPECT_NEAR(to_seconds(moved.fixes[5].t - base.fixes[5].t), 0.03, 0.0021);
  EXPECT_EQ(moved.fixes[5].utc_ns, base.fixes[5].utc_ns);  // the receiver's UTC is not the logger's clock
  ASSERT_EQ(base.frames.size(), moved.frames.size());
  EXPECT_NEAR(to_seconds(moved.frames[100].t - base.frames[100].t), 0.00092, 0.00003);
  ASSERT_FALSE(moved.weather_samples.empty());
  EXPECT_EQ(to_ns(moved.weather_samples[0].t) - to_ns(base.weather_samples[0].t), -500'000'000);
}

}  // namespace
}  // namespace roadload::sim
