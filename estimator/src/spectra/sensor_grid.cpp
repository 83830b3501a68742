#include "roadload/spectra/sensor_grid.hpp"

#include <cmath>
#include <complex>
#include <limits>
#include <numbers>

namespace roadload::spectra {

std::array<Biquad, 2> butterworth_lowpass4(double cutoff_hz, double fs_hz) {
  // Poles of the 4th-order Butterworth in two pairs, Q = 1 / (2 cos(pi/8)) and 1 / (2 cos(3 pi/8)).
  const double qs[2] = {1.0 / (2.0 * std::cos(std::numbers::pi / 8)), 1.0 / (2.0 * std::cos(3 * std::numbers::pi / 8))};
  const double w0 = 2.0 * std::numbers::pi * cutoff_hz / fs_hz;
  std::array<Biquad, 2> out;
  for (int i = 0; i < 2; ++i) {
    const double alpha = std::sin(w0) / (2.0 * qs[i]), c = std::cos(w0), a0 = 1.0 + alpha;
    Biquad& b = out[static_cast<std::size_t>(i)];
    b.b0 = (1.0 - c) / 2.0 / a0;
    b.b1 = (1.0 - c) / a0;
    b.b2 = b.b0;
    b.a1 = -2.0 * c / a0;
    b.a2 = (1.0 - alpha) / a0;
  }
  return out;
}

double Biquad::power_gain(double w) const {
  const std::complex<double> z1i = std::polar(1.0, -w), z2i = z1i * z1i;
  return std::norm((b0 + b1 * z1i + b2 * z2i) / (1.0 + a1 * z1i + a2 * z2i));
}

VelocityIntegrator::VelocityIntegrator(double fs_hz, double highpass_hz, double leak_hz)
    : rho(std::exp(-2.0 * std::numbers::pi * leak_hz / fs_hz)), half_period_s(0.5 / fs_hz) {
  const double w0 = 2.0 * std::numbers::pi * highpass_hz / fs_hz;
  const double alpha = std::sin(w0) / std::numbers::sqrt2, c = std::cos(w0), a0 = 1.0 + alpha;
  highpass.b0 = (1.0 + c) / 2.0 / a0;
  highpass.b1 = -(1.0 + c) / a0;
  highpass.b2 = highpass.b0;
  highpass.a1 = -2.0 * c / a0;
  highpass.a2 = (1.0 - alpha) / a0;
}

void VelocityIntegrator::reset(double a) {
  highpass.settle(a, 0.0);
  last_a = 0;
  v = 0;
}

double VelocityIntegrator::step(double a) {
  const double hp = highpass.step(a);
  v = rho * v + half_period_s * (hp + last_a);
  last_a = hp;
  return v;
}

double VelocityIntegrator::response_ratio(double f_hz, double fs_hz) const {
  const double w = 2.0 * std::numbers::pi * f_hz / fs_hz;
  const std::complex<double> zi = std::polar(1.0, -w);
  const double integrator = std::norm(half_period_s * (1.0 + zi) / (1.0 - rho * zi));
  const double omega = 2.0 * std::numbers::pi * f_hz;
  return highpass.power_gain(w) * integrator * omega * omega;
}

SensorGrid::SensorGrid(std::span<const GridSensor> sensors, GridConfig config)
    : config_(config),
      integrator_(1e9 / static_cast<double>(config.period_ns), config.velocity_highpass_hz, config.velocity_leak_hz),
      latest_(std::numeric_limits<std::int64_t>::min()) {
  const double grid_hz = rate_hz();
  for (const GridSensor& g : sensors) {
    Sensor s;
    s.info = g;
    // A sensor slower than the grid is passed through unfiltered: it cannot alias onto it.
    const double cutoff = config_.cutoff_fraction * grid_hz;
    if (g.rate_hz > 2.0 * cutoff) s.filter = butterworth_lowpass4(cutoff, g.rate_hz);
    s.gap_ns = static_cast<std::int64_t>(config_.gap_periods * 1e9 / g.rate_hz);
    s.values.assign(config_.history, 0.0);
    s.velocity.assign(config_.history, 0.0);
    s.integrator = integrator_;
    s.index.assign(config_.history, std::numeric_limits<std::int64_t>::min());
    sensors_.push_back(std::move(s));
  }
}

int SensorGrid::slot(std::uint8_t id) const {
  for (std::size_t i = 0; i < sensors_.size(); ++i)
    if (sensors_[i].info.id == id) return static_cast<int>(i);
  return -1;
}

void SensorGrid::put(Sensor& s, std::int64_t n, double v) {
  if (n < 0) return;  // before the capture clock's epoch: never a real stamp
  const auto k = static_cast<std::size_t>(n % static_cast<std::int64_t>(config_.history));
  if (!s.integrating) {
    s.integrator.reset(v);
    s.warm_from = n;
    s.ready_from = n + static_cast<std::int64_t>(std::ceil(config_.warmup.count() * rate_hz()));
  }
  s.integrating = true;
  s.values[k] = v;
  s.velocity[k] = s.integrator.step(v);
  s.index[k] = n;
  if (n > latest_) latest_ = n;
}

void SensorGrid::push(const AccelSample& sample) {
  const int i = slot(sample.sensor);
  if (i < 0) return;
  Sensor& s = sensors_[static_cast<std::size_t>(i)];
  if (s.started && (sample.t - s.last_t).count() > s.gap_ns) {
    s.started = false;
    ++restarts_;
  }
  if (!s.started) {
    for (Biquad& b : s.filter) b.settle(sample.z_mps2, sample.z_mps2);
    s.integrating = false;
  }
  double y = sample.z_mps2;
  for (Biquad& b : s.filter) y = b.step(y);
  const std::int64_t t1 = to_ns(sample.t), p = config_.period_ns;
  if (s.started && sample.t > s.last_t) {
    // Grid instants in (last_t, t]: interpolate between the two filtered samples. The first is
    // carried from the last sample rather than divided out again: a division a sample cost more
    // than the rest of the interpolation.
    const std::int64_t t0 = to_ns(s.last_t);
    std::int64_t n = s.next_n;
    for (; n * p <= t1; ++n) {
      const double w = static_cast<double>(n * p - t0) / static_cast<double>(t1 - t0);
      put(s, n, s.last_y + w * (y - s.last_y));
    }
    s.next_n = n;
  } else if (!s.started || sample.t < s.last_t) {
    s.next_n = (t1 >= 0 ? t1 / p : -((-t1 + p - 1) / p)) + 1;  // floor(t1 / p) + 1
  }
  s.started = true;
  s.last_t = sample.t;
  s.last_y = y;
}

bool SensorGrid::copy(std::size_t slot_index, std::int64_t end, std::span<double> out) const {
  return copy_from(slot_index, end, out, false);
}

bool SensorGrid::value_at(std::size_t slot_index, std::int64_t n, double& out) const {
  return copy_from(slot_index, n, std::span<double>(&out, 1), false);
}

bool SensorGrid::copy_velocity(std::size_t slot_index, std::int64_t end, std::span<double> out) const {
  return copy_from(slot_index, end, out, true);
}

bool SensorGrid::copy_from(std::size_t slot_index, std::int64_t end, std::span<double> out, bool velocity) const {
  const Sensor& s = sensors_[slot_index];
  const std::vector<double>& src = velocity ? s.velocity : s.values;
  const auto h = static_cast<std::int64_t>(config_.history);
  const auto n = static_cast<std::int64_t>(out.size());
  const std::int64_t first = end - n + 1;
  if (n > h || (first < s.ready_from && end >= s.warm_from)) return false;
  if (n == 0) return true;
  if (first < 0) return false;
  // One remainder for the run, then the ring's index steps on: one a value cost as much as the copy.
  auto k = static_cast<std::size_t>(first % h);
  for (std::int64_t j = 0; j < n; ++j) {
    if (s.index[k] != first + j) return false;
    out[static_cast<std::size_t>(j)] = src[k];
    if (++k == src.size()) k = 0;
  }
  return true;
}

}  // namespace roadload::spectra
