// The vibration pipeline on a synthetic truck whose motion is known: one axle bouncing on its
// suspension at 10 Hz under a still frame, sensors on their own clocks.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <numbers>
#include <vector>

#include "allocation_counter.hpp"
#include "roadload/vibration.hpp"
#include "vehicles.hpp"

namespace roadload {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

AxleLayout front_axle_only() {
  const SensorPlacement placements[] = {{0, "accelerometer", "tractor-front-axle-left"},
                                        {1, "accelerometer", "tractor-front-frame-left"}};
  Vehicle front = shipped::mnroad_vehicle();
  front.axles.resize(1);
  auto l = build_axle_layout(placements, front);
  EXPECT_TRUE(l.ok());
  return l.value();
}

struct Drive {
  double freq_hz = 10, accel_amp = 2.0, speed_mps = 13.4;
  double seconds = 60;
};

// Axle at 1200 Hz, frame at 1190 Hz (a part 0.8 % slow), both reading 1 g plus their motion.
void drive(VibrationAnalysis& va, const Drive& d, double cell_m) {
  double ta = 1.0, tf = 1.0002, next_place = 1.0;
  std::array<int, 1> cell{};
  while (ta < 1.0 + d.seconds) {
    if (ta >= next_place) {
      cell[0] = static_cast<int>(d.speed_mps * (next_place - 1.0) / cell_m);
      va.set_axle_cells(capture_time_from_ns(std::llround(next_place * 1e9)), cell, d.speed_mps, d.speed_mps * (next_place - 1.0));
      next_place += 0.1;
    }
    AccelSample s;
    if (ta <= tf) {
      s.t = capture_time_from_ns(std::llround(ta * 1e9));
      s.sensor = 0;
      s.z_mps2 = 9.81 + d.accel_amp * std::sin(kTwoPi * d.freq_hz * ta);
      ta += 1.0 / 1200.0;
    } else {
      s.t = capture_time_from_ns(std::llround(tf * 1e9));
      s.sensor = 1;
      s.z_mps2 = 9.81;
      tf += 1.0 / 1190.0;
    }
    va.push(s);
  }
}

std::vector<VibrationSensor> sensors() { return {{0, "TLF1", 1200.0}, {1, "TLF2", 1200.0}}; }

TEST(VibrationAnalysis, DamperPowerOfAKnownRelativeMotion) {
  VibrationAnalysis va(front_axle_only(), sensors(), 10, std::vector<int>(10, 0), 1);
  const Drive d;
  drive(va, d, 100.0);
  // Relative velocity amplitude a / w: P = c v^2 / 2 with the report's 20,000 N s/m.
  const double v = d.accel_amp / (kTwoPi * d.freq_hz);
  const double expected = 20000.0 * v * v / 2;
  EXPECT_NEAR(va.trip_power().damper_w, expected, 0.01 * expected);
  // Cells of 100 m at 13.4 m/s: every whole cell sees the same power.
  for (std::size_t c = 1; c < 7; ++c) EXPECT_NEAR(va.cell_power(c).damper_w, expected, 0.02 * expected) << "cell " << c;
  // The frame is still: Eq. 2.7 on the axle's absolute motion with 2 tires x 4,000 N s/m.
  EXPECT_NEAR(va.trip_power().tire_eq27_w, 8000.0 * v * v / 2, 0.01 * 8000.0 * v * v / 2);
}

// A cell keeps its powers' sums rather than its spectra: a cell holding the whole drive has the
// trip's power, which comes from the spectra.
TEST(VibrationAnalysis, ACellOverTheWholeDriveHasTheTripsPower) {
  VibrationAnalysis va(front_axle_only(), sensors(), 1, std::vector<int>(1, 0), 1);
  Drive d;
  d.accel_amp = 1.0;
  drive(va, d, 1e6);
  const DynamicPower trip = va.trip_power(), cell = va.cell_power(0);
  ASSERT_GT(trip.segments, 100.0);
  EXPECT_NEAR(cell.segments, trip.segments, 1e-9 * trip.segments);
  for (double DynamicPower::*f :
       {&DynamicPower::damper_w, &DynamicPower::damper_accel_w, &DynamicPower::tire_w, &DynamicPower::tire_eq27_w}) {
    EXPECT_GT(trip.*f, 0.0);
    EXPECT_NEAR(cell.*f, trip.*f, 1e-9 * trip.*f);
  }
}

TEST(VibrationAnalysis, WindowPowerRestartsWhenCleared) {
  VibrationAnalysis va(front_axle_only(), sensors(), 10, std::vector<int>(10, 0), 1);
  Drive d;
  d.seconds = 20;
  drive(va, d, 100.0);
  EXPECT_GT(va.window_power().segments, 10.0);
  va.clear_window();
  EXPECT_EQ(va.window_power().segments, 0.0);
  EXPECT_GT(va.trip_power().segments, 10.0);
}

TEST(VibrationAnalysis, PushDoesNotAllocate) {
  VibrationAnalysis va(front_axle_only(), sensors(), 10, std::vector<int>(10, 0), 1);
  Drive d;
  d.seconds = 15;
  drive(va, d, 100.0);  // past the first segments of every kind
  std::size_t allocations = 0;
  {
    test::CountAllocations count;
    AccelSample s;
    for (int i = 0; i < 24000; ++i) {
      s.t = capture_time_from_ns(std::llround((16.1 + i / 2400.0) * 1e9));
      s.sensor = static_cast<std::uint8_t>(i % 2);
      s.z_mps2 = 9.81 + 0.1 * std::sin(0.01 * i);
      va.push(s);
      if (i % 240 == 0) {
        const std::array<int, 1> cell{2};
        va.set_axle_cells(s.t, cell, 13.4, 200.0 + i * 0.0056);
      }
    }
    allocations = count.count();
  }
  EXPECT_EQ(allocations, 0u);
}

}  // namespace
}  // namespace roadload
