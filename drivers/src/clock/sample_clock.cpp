#include "roadload/clock/sample_clock.hpp"

#include <algorithm>
#include <cmath>

namespace roadload::clock {

SampleClock::SampleClock(SampleClockConfig config) : config_(config), period_s_(1.0 / config.nominal_rate_hz) {
  config_.window_edges = std::clamp<std::size_t>(config_.window_edges, 2, kMaxEdges);
}

void SampleClock::restart() {
  started_ = false;
  n_ = 0;
  head_ = 0;
}

CaptureTime SampleClock::edge(CaptureTime t, std::uint32_t samples) {
  if (!started_) {
    started_ = true;
    origin_ = t;
    count_ = 0;
    intercept_s_ = 0;
  } else {
    count_ += samples;
  }
  edges_[head_] = {count_, to_seconds(t - origin_)};
  head_ = (head_ + 1) % config_.window_edges;
  n_ = std::min(n_ + 1, config_.window_edges);
  if (n_ >= 2) fit();
  const double newest_s = intercept_s_ + count_ * period_s_ - config_.output_delay.count();
  return origin_ + Nanoseconds{std::llround(newest_s * 1e9)};
}

void SampleClock::fit() {
  double mc = 0, mt = 0;
  for (std::size_t i = 0; i < n_; ++i) {
    mc += edges_[i].count;
    mt += edges_[i].t_s;
  }
  mc /= static_cast<double>(n_);
  mt /= static_cast<double>(n_);
  double scc = 0, sct = 0;
  for (std::size_t i = 0; i < n_; ++i) {
    scc += (edges_[i].count - mc) * (edges_[i].count - mc);
    sct += (edges_[i].count - mc) * (edges_[i].t_s - mt);
  }
  if (scc <= 0) return;
  const double period = sct / scc;
  const double nominal = 1.0 / config_.nominal_rate_hz;
  if (std::abs(period / nominal - 1.0) > config_.max_rate_error) return;
  period_s_ = period;
  // The line through the earliest edges: latency is one-sided, so lower the fit to the edge that
  // lies furthest below it.
  double lowest = 0;
  for (std::size_t i = 0; i < n_; ++i) lowest = std::min(lowest, edges_[i].t_s - (mt + (edges_[i].count - mc) * period));
  intercept_s_ = mt - mc * period + lowest;
}

}  // namespace roadload::clock
