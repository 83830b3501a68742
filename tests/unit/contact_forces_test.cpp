// Contact forces of Eq. 2.1 on synthetic accelerometer streams with known answers: sinusoidal
// axle and frame motions give a known F_z mean and standard deviation; sensor offsets do not leak
// into the force; unpaired, stale and unplaced samples are counted; the layout names what is missing.
#include "roadload/contact_forces.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <functional>
#include <numbers>
#include <vector>

#include "allocation_counter.hpp"
#include "contact_layout.hpp"

namespace roadload {
namespace {

constexpr double kG = 9.80665;
constexpr double kPi = std::numbers::pi;
constexpr double kSpeed = 13.41;  // 30 mph

using namespace contact_test;

// Samples of every sensor at `rate_hz`, each sensor on its own phase of the sample clock, merged in
// time order. accel(sensor, t) is the true vertical acceleration without g; the part adds g,
// its offset and gain.
struct Stream {
  double rate_hz = 1200.0;
  double duration_s = 60.0;
  std::function<double(std::size_t, double)> accel;
  std::function<double(std::size_t)> offset = [](std::size_t s) { return 0.2 * std::sin(1.0 + static_cast<double>(s)); };
  std::function<bool(std::size_t, double)> present = [](std::size_t, double) { return true; };
  std::size_t sensors = 8;

  std::vector<AccelSample> samples() const {
    std::vector<AccelSample> out;
    const auto n = static_cast<std::int64_t>(duration_s * rate_hz);
    for (std::int64_t k = 0; k < n; ++k) {
      for (std::size_t s = 0; s < sensors; ++s) {
        // Sensor s samples 0.05 ms after sensor s-1 within each period.
        const double t = static_cast<double>(k) / rate_hz + 5e-5 * static_cast<double>(s);
        if (!present(s, t)) continue;
        AccelSample a;
        a.t = capture_time_from_ns(std::llround(t * 1e9));
        a.sensor = static_cast<std::uint8_t>(s);
        a.z_mps2 = kG + accel(s, t) + offset(s);
        a.x_mps2 = offset(s + 10);
        out.push_back(a);
      }
    }
    return out;
  }
};

// Frame of axle unit u moves A_c sin(w1 t + phi_u); axle i moves A_w sin(w1 t) + B_w sin(w2 t).
constexpr double kW1 = 2 * kPi * 1.5, kW2 = 2 * kPi * 12.0;
constexpr double kAc = 0.4, kAw = 1.0, kBw = 3.0;
double frame_phase(std::size_t sensor) { return 0.3 + 0.7 * static_cast<double>(sensor); }
bool is_frame(std::size_t s) { return s == 1 || s == 3 || s == 6; }
double motion(std::size_t s, double t) {
  if (is_frame(s)) return kAc * std::sin(kW1 * t + frame_phase(s));
  return kAw * std::sin(kW1 * t) + kBw * std::sin(kW2 * t);
}

// Standard deviation of M_w a_w + M_c a_c for these sinusoids, a borrowed frame read
// frame_ahead_m / speed earlier (speed 0: undelayed).
double expected_dynamic_std(const AxleContact& a, double speed_mps = kSpeed) {
  const double delay_s = speed_mps > 0 ? a.frame_ahead_m / speed_mps : 0.0;
  const std::complex<double> at_w1 = a.unsprung_kg * kAw +
                                     a.sprung_kg * kAc * std::polar(1.0, frame_phase(a.frame_sensor) - kW1 * delay_s);
  const double at_w2 = a.unsprung_kg * kBw;
  return std::sqrt((std::norm(at_w1) + at_w2 * at_w2) / 2.0);
}

TEST(ContactForces, SinusoidalAxleAndFrameMotionsGiveTheKnownMeanAndStandardDeviation) {
  const AxleLayout layout = mnroad_layout();
  Stream st;
  st.duration_s = 65.0;  // 60 s after the warm-up: whole periods of both sinusoids
  st.accel = motion;
  const auto samples = st.samples();
  ContactForces cf(layout, 1);
  const double grade = 0.01;
  cf.set_cell(capture_time_from_ns(0), 0, grade, kSpeed);
  for (const auto& s : samples) {
    if (s.sensor == 0) cf.set_cell(s.t, 0, grade, kSpeed);  // the position, refreshed as a caller would
    cf.push(s);
  }
  for (std::size_t i = 0; i < layout.axles.size(); ++i) {
    const AxleContact& a = layout.axles[i];
    const AxleForceStats r = cf.cell(0, i);
    const double want_mean = a.load_kg * kG * std::cos(grade);
    const double want_std = expected_dynamic_std(a);
    // The running mean's 0.05 Hz cut-off takes 0.06 % at 1.5 Hz; sampling and the finite record
    // a little more.
    EXPECT_NEAR(r.fz.mean_n, want_mean, 1e-4 * want_mean) << a.name;
    EXPECT_NEAR(r.dynamic.mean_n, 0.0, 1e-4 * want_mean) << a.name;
    EXPECT_NEAR(r.dynamic.std_n, want_std, 0.003 * want_std) << a.name;
    EXPECT_NEAR(r.fz.std_n, want_std, 0.003 * want_std) << a.name;
    // 60 s after the 5 s warm-up at 1200 Hz.
    EXPECT_NEAR(static_cast<double>(r.fz.count), 60.0 * 1200.0, 2.0) << a.name;
    EXPECT_EQ(cf.counters(i).stale_frame, 0u);
    EXPECT_EQ(cf.counters(i).no_cell, 0u);
    EXPECT_EQ(cf.trip(i).fz.count, r.fz.count);
    // F_RR = CRR x F_z, dynamic part included.
    const ForceStats rr = rolling_resistance(r.fz, 0.0055);
    EXPECT_DOUBLE_EQ(rr.mean_n, 0.0055 * r.fz.mean_n);
    EXPECT_DOUBLE_EQ(rr.std_n, 0.0055 * r.fz.std_n);
    EXPECT_TRUE(cf.latest(i).valid);
    EXPECT_DOUBLE_EQ(rolling_resistance_n(0.0055, cf.latest(i).fz_n), 0.0055 * cf.latest(i).fz_n);
  }
  EXPECT_EQ(cf.unknown_sensor_samples(), 0u);
}

TEST(ContactForces, SensorOffsetsDoNotReachTheForce) {
  // A sensor reading 25 mg high and another 25 mg low: the static force is still the axle load.
  const AxleLayout layout = mnroad_layout();
  Stream st;
  st.duration_s = 20.0;
  st.accel = [](std::size_t, double) { return 0.0; };
  st.offset = [](std::size_t s) { return (s % 2 == 0 ? 0.025 : -0.025) * kG; };
  ContactForces cf(layout, 1);
  cf.set_cell(capture_time_from_ns(0), 0, 0.0, kSpeed);
  for (const auto& s : st.samples()) {
    cf.set_cell(s.t, 0, 0.0, kSpeed);
    cf.push(s);
  }
  for (std::size_t i = 0; i < layout.axles.size(); ++i) {
    EXPECT_GT(cf.cell(0, i).fz.count, 0u);
    EXPECT_NEAR(cf.cell(0, i).fz.mean_n, layout.axles[i].load_kg * kG, 1e-6 * layout.axles[i].load_kg * kG);
    EXPECT_NEAR(cf.cell(0, i).dynamic.std_n, 0.0, 1e-6);
  }
}

TEST(ContactForces, CountsAxleSamplesWhoseFrameSampleIsTooOld) {
  // The drive1 frame sensor (3, also drive2's) falls silent for 0.2 s at t = 30 s: shorter than
  // the 0.5 s restart gap, so its running mean is kept; axle samples more than 5 ms after its
  // last sample are counted, not paired.
  const AxleLayout layout = mnroad_layout();
  Stream st;
  st.duration_s = 40.0;
  st.accel = motion;
  st.present = [](std::size_t s, double t) { return s != 3 || t < 30.0 || t >= 30.2; };
  ContactForces cf(layout, 1);
  cf.set_cell(capture_time_from_ns(0), 0, 0.0, kSpeed);
  for (const auto& s : st.samples()) {
    cf.set_cell(s.t, 0, 0.0, kSpeed);
    cf.push(s);
  }
  // drive1: axle samples from 5 ms after the frame's last one until it resumes, ~0.195 s x 1200 Hz.
  // drive2 reads that frame 1.32 m / 13.41 m/s = 98 ms earlier, with samples on both sides of the
  // gap: ~0.190 s.
  EXPECT_NEAR(static_cast<double>(cf.counters(1).stale_frame), 0.195 * 1200, 2.0);
  EXPECT_NEAR(static_cast<double>(cf.counters(2).stale_frame), 0.190 * 1200, 2.0);
  for (std::size_t i : {1u, 2u}) {
    EXPECT_EQ(cf.counters(i).paired + cf.counters(i).stale_frame + cf.counters(i).warming_up + cf.counters(i).no_frame,
              static_cast<std::uint64_t>(40 * 1200));
  }
  for (std::size_t i : {0u, 3u, 4u}) EXPECT_EQ(cf.counters(i).stale_frame, 0u) << layout.axles[i].name;
  EXPECT_EQ(cf.sensor_restarts(), 0u);
  // The statistics are those of the paired samples, still right.
  EXPECT_NEAR(cf.cell(0, 1).dynamic.std_n, expected_dynamic_std(layout.axles[1]), 0.005 * expected_dynamic_std(layout.axles[1]));
}

TEST(ContactForces, ABorrowedFrameIsReadSpreadOverSpeedEarlier) {
  // drive2 and trailer2 borrow drive1's and trailer1's frame sensors, 1.32 m and 1.24 m ahead: at
  // 13.41 m/s their body term is that frame's motion 98 ms and 92 ms earlier. Without a speed
  // (NaN) it is read undelayed and counted as such.
  const AxleLayout layout = mnroad_layout();
  EXPECT_NEAR(layout.axles[2].frame_ahead_m, 1.32, 1e-12);
  EXPECT_NEAR(layout.axles[4].frame_ahead_m, 1.24, 1e-12);
  EXPECT_EQ(layout.axles[1].frame_ahead_m, 0.0);
  Stream st;
  st.duration_s = 65.0;
  st.accel = motion;
  const auto samples = st.samples();
  for (const double speed : {kSpeed, std::nan("")}) {
    ContactForces cf(layout, 1);
    for (const auto& s : samples) {
      cf.set_cell(s.t, 0, 0.0, speed);
      cf.push(s);
    }
    const bool delayed = !std::isnan(speed);
    for (std::size_t i : {2u, 4u}) {
      const double want = expected_dynamic_std(layout.axles[i], delayed ? speed : 0.0);
      const double other = expected_dynamic_std(layout.axles[i], delayed ? 0.0 : kSpeed);
      EXPECT_GT(std::abs(want / other - 1.0), 0.05) << "the delay must matter for this check";
      EXPECT_NEAR(cf.cell(0, i).dynamic.std_n, want, 0.003 * want) << layout.axles[i].name << (delayed ? " delayed" : " undelayed");
      EXPECT_EQ(cf.counters(i).undelayed, delayed ? 0u : cf.counters(i).paired) << layout.axles[i].name;
    }
    EXPECT_EQ(cf.counters(1).undelayed, 0u);  // drive1 has its own frame
  }
}

TEST(ContactForces, CountsAxleSamplesWithoutAnyFrameSample) {
  const AxleLayout layout = mnroad_layout();
  Stream st;
  st.duration_s = 10.0;
  st.accel = motion;
  st.present = [](std::size_t s, double) { return s != 6; };  // the trailer frame never reports
  ContactForces cf(layout, 1);
  cf.set_cell(capture_time_from_ns(0), 0, 0.0, kSpeed);
  for (const auto& s : st.samples()) cf.push(s);
  for (std::size_t i : {3u, 4u}) {
    EXPECT_EQ(cf.counters(i).paired, 0u);
    EXPECT_NEAR(static_cast<double>(cf.counters(i).no_frame), 5.0 * 1200, 2.0);
    EXPECT_EQ(cf.cell(0, i).fz.count, 0u);
  }
  EXPECT_GT(cf.counters(0).paired, 0u);
}

TEST(ContactForces, AGapRestartsASensorsRunningMeanAndWarmUp) {
  const AxleLayout layout = mnroad_layout();
  Stream st;
  st.duration_s = 30.0;
  st.accel = motion;
  st.present = [](std::size_t s, double t) { return s != 0 || t < 10.0 || t >= 12.0; };
  ContactForces cf(layout, 1);
  cf.set_cell(capture_time_from_ns(0), 0, 0.0, kSpeed);
  for (const auto& s : st.samples()) {
    cf.set_cell(s.t, 0, 0.0, kSpeed);
    cf.push(s);
  }
  EXPECT_EQ(cf.sensor_restarts(), 1u);
  // Warm-up twice: 0-5 s and 12-17 s.
  EXPECT_NEAR(static_cast<double>(cf.counters(0).warming_up), 10.0 * 1200, 2.0);
}

TEST(ContactForces, SamplesOutsideEveryCellOrWithAStalePositionAreCountedNotAccumulated) {
  const AxleLayout layout = mnroad_layout();
  Stream st;
  st.duration_s = 20.0;
  st.accel = motion;
  ContactForces cf(layout, 3);
  const auto samples = st.samples();
  for (const auto& s : samples) {
    const double t = to_seconds(s.t.time_since_epoch());
    // Each axle in its own cell; from 15 s on the position is no longer refreshed.
    if (t < 15.0) {
      const std::array<int, 5> cells = {0, 1, 1, 2, -1};
      cf.set_axle_cells(s.t, cells, 0.0, kSpeed);
    }
    cf.push(s);
  }
  // Paired 5-20 s; placed 5-17 s (position valid 2 s after its last refresh).
  EXPECT_NEAR(static_cast<double>(cf.cell(0, 0).fz.count), 12.0 * 1200, 2.0);
  EXPECT_NEAR(static_cast<double>(cf.cell(1, 1).fz.count), 12.0 * 1200, 2.0);
  EXPECT_NEAR(static_cast<double>(cf.cell(1, 2).fz.count), 12.0 * 1200, 2.0);
  EXPECT_NEAR(static_cast<double>(cf.cell(2, 3).fz.count), 12.0 * 1200, 2.0);
  EXPECT_EQ(cf.cell(0, 1).fz.count, 0u);
  EXPECT_EQ(cf.cell(2, 4).fz.count, 0u);
  EXPECT_NEAR(static_cast<double>(cf.counters(0).no_cell), 3.0 * 1200, 2.0);
  EXPECT_NEAR(static_cast<double>(cf.counters(4).no_cell), 15.0 * 1200, 2.0);
  EXPECT_EQ(cf.trip(4).fz.count, cf.counters(4).paired);
}

TEST(ContactForces, CountsSamplesOfSensorsNotInTheLayout) {
  ContactForces cf(mnroad_layout(), 1);
  AccelSample s;
  s.sensor = 42;
  cf.push(s);
  cf.push(s);
  EXPECT_EQ(cf.unknown_sensor_samples(), 2u);
}

TEST(ContactForces, APushIsFreeOfHeapAllocations) {
  Stream st;
  st.duration_s = 10.0;
  st.accel = motion;
  const auto samples = st.samples();
  ContactForces cf(mnroad_layout(), 30);
  std::size_t allocations = 0;
  {
    const test::CountAllocations count;
    for (const auto& s : samples) {
      cf.set_cell(s.t, 7, 0.002, kSpeed);
      cf.push(s);
    }
    allocations = count.count();
  }
  EXPECT_EQ(allocations, 0u);
  EXPECT_GT(cf.cell(7, 0).fz.count, 0u);
}

}  // namespace
}  // namespace roadload
