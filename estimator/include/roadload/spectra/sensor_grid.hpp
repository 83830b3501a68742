#pragma once
// Accelerometers on one time grid. Each part samples on its own oscillator (an ADXL355's runs
// +-few % off nominal and drifts), so two sensors' n-th samples are not simultaneous; a
// cross-spectrum between an axle and the frame above it needs both at the same instants. Each
// sensor's z is low-passed at its own rate (4th-order Butterworth, anti-alias), then read by
// linear interpolation at every instant t = n / fs of the capture clock between the two samples
// around it. Grid values are kept per sensor in a ring; a segment is handed out only if every one of
// its instants is there (a gap or a restart leaves holes, and that sensor sits those segments out).
//
// Pure computation; storage is sized at construction and push() never allocates.
#include <array>
#include <cstdint>
#include <limits>
#include <span>
#include <vector>

#include "roadload/samples.hpp"
#include "roadload/time.hpp"

namespace roadload::spectra {

// Transposed direct form II; settle() sets the state for a steady input x with steady output y, so
// the static 1 g starts no transient.
struct Biquad {
  double b0 = 1, b1 = 0, b2 = 0, a1 = 0, a2 = 0;
  double z1 = 0, z2 = 0;
  double step(double x) {
    const double y = b0 * x + z1;
    z1 = b1 * x - a1 * y + z2;
    z2 = b2 * x - a2 * y;
    return y;
  }
  void settle(double x, double y) {
    z2 = b2 * x - a2 * y;
    z1 = b1 * x - a1 * y + z2;
  }
  // |H(e^{i w})|^2 at w = 2 pi f / fs.
  double power_gain(double w) const;
};

// Acceleration to velocity on the grid: a 2nd-order Butterworth high-pass (the static 1 g and the
// part's offset wander out) and a leaky trapezoidal integrator. Its departure from the ideal
// 1 / (i w) is known exactly (response_ratio) and divided out of the velocity's density, so the
// 1 / (2 pi f)^2 of Eq. 2.7-2.8 is applied before the Welch window rather than after it: the
// window's main lobe would otherwise carry the 1.5 Hz body modes into the lowest bins, where the
// weight multiplies them by up to four (+11 % on the simulated Mainline).
struct VelocityIntegrator {
  Biquad highpass;
  double rho = 1, half_period_s = 0;
  double last_a = 0, v = 0;
  VelocityIntegrator() = default;
  VelocityIntegrator(double fs_hz, double highpass_hz, double leak_hz);
  void reset(double a);
  double step(double a);
  // |H(f)|^2 (2 pi f)^2: 1 for an ideal integrator.
  double response_ratio(double f_hz, double fs_hz) const;
};

// Butterworth low-pass of order 4 at cutoff_hz for a rate of fs_hz, as two biquads (bilinear).
std::array<Biquad, 2> butterworth_lowpass4(double cutoff_hz, double fs_hz);

struct GridConfig {
  std::int64_t period_ns = 5'000'000;  // 200 Hz: body, joint, tandem and axle-hop modes (< 20 Hz) and 5 harmonics of the joint line
  double cutoff_fraction = 0.4;        // anti-alias corner at 0.4 x the grid rate: 80 Hz, 0.1 % down at 30 Hz
  double gap_periods = 4.5;            // a sensor silent for more of its own periods restarts
  std::size_t history = 4096;          // grid values kept per sensor (20 s at 200 Hz)
  double velocity_highpass_hz = 0.1;   // a decade below the 1.5 Hz body modes
  double velocity_leak_hz = 0.05;
  // Grid values this soon after a sensor's (re)start are held back: the integrator's leak takes
  // its unknown initial velocity out with a 3.2 s time constant.
  Seconds warmup{10.0};
};

struct GridSensor {
  std::uint8_t id = 0;  // accel.csv sensor id
  double rate_hz = 0;   // nominal output rate
};

class SensorGrid {
 public:
  SensorGrid(std::span<const GridSensor> sensors, GridConfig config = {});

  // One sample, in capture-time order across sensors; samples of other sensors are ignored.
  void push(const AccelSample& s);

  const GridConfig& config() const { return config_; }
  double rate_hz() const { return 1e9 / static_cast<double>(config_.period_ns); }
  CaptureTime time_of(std::int64_t n) const { return capture_time_from_ns(n * config_.period_ns); }
  // Highest grid index any sensor has reached; INT64_MIN before the first sample.
  std::int64_t latest() const { return latest_; }
  // Slot of a sensor id, or -1.
  int slot(std::uint8_t id) const;
  std::size_t sensor_count() const { return sensors_.size(); }
  // Values of grid instants end-out.size()+1 .. end of one sensor; false if any is missing.
  bool copy(std::size_t slot, std::int64_t end, std::span<double> out) const;
  // One grid value; false if missing.
  bool value_at(std::size_t slot, std::int64_t n, double& out) const;
  // The same of the velocity integrated on the grid (VelocityIntegrator).
  bool copy_velocity(std::size_t slot, std::int64_t end, std::span<double> out) const;
  // The integrator's power response over the ideal 1 / (2 pi f)^2 at f.
  double velocity_response_ratio(double f_hz) const { return integrator_.response_ratio(f_hz, rate_hz()); }
  std::uint64_t restarts() const { return restarts_; }

 private:
  struct Sensor {
    GridSensor info;
    std::array<Biquad, 2> filter;
    std::int64_t gap_ns = 0;
    bool started = false;
    CaptureTime last_t{};
    double last_y = 0;
    std::int64_t next_n = 0;  // the first grid instant after last_t, once started
    std::vector<double> values, velocity;
    std::vector<std::int64_t> index;  // grid index held in each ring slot
    VelocityIntegrator integrator;
    bool integrating = false;
    std::int64_t warm_from = 0, ready_from = 0;  // the latest warm-up's grid indices, not handed out
  };
  void put(Sensor& s, std::int64_t n, double v);
  bool copy_from(std::size_t slot, std::int64_t end, std::span<double> out, bool velocity) const;

  GridConfig config_;
  VelocityIntegrator integrator_;
  std::vector<Sensor> sensors_;
  std::int64_t latest_;
  std::uint64_t restarts_ = 0;
};

// When segments of `length` grid samples are due, one every `hop`, from the first grid value on:
// each is taken once the grid has moved `lag` samples past its end, so every sensor has had the
// chance to fill it.
class SegmentSchedule {
 public:
  SegmentSchedule(std::size_t length, std::size_t hop, std::int64_t lag)
      : length_(static_cast<std::int64_t>(length)), hop_(static_cast<std::int64_t>(hop)), lag_(lag) {}
  // Calls take(end) for each segment now due, in order.
  template <typename Take>
  void run(const SensorGrid& grid, Take&& take) {
    if (grid.latest() == std::numeric_limits<std::int64_t>::min()) return;
    if (!started_) {
      next_end_ = grid.latest() + length_ - 1;
      started_ = true;
    }
    for (; grid.latest() >= next_end_ + lag_; next_end_ += hop_) take(next_end_);
  }

 private:
  std::int64_t length_, hop_, lag_;
  std::int64_t next_end_ = 0;
  bool started_ = false;
};

}  // namespace roadload::spectra
