#pragma once
// Times of accelerometer samples read from a FIFO. The part's data-ready line interrupts with a
// kernel timestamp (libgpiod 1.6 line events: CLOCK_MONOTONIC on Linux >= 5.7); a burst read then
// empties the FIFO. The newest sample of the burst was taken at the edge (less the part's fixed
// output delay); the older ones one output period apart before it. The period is the part's own
// oscillator's, a few percent off nominal and drifting with temperature, so it is measured: a
// least-squares line through (sample count, edge time) over a sliding window of edges. Interrupt
// latency only delays edges (never advances them), so the line is fitted to the earliest edges:
// each edge's residual is clipped from above before it enters the fit.
//
// Pure computation: the caller passes the edge stamps and sample counts in.
#include <array>
#include <cstdint>

#include "roadload/time.hpp"

namespace roadload::clock {

struct SampleClockConfig {
  double nominal_rate_hz = 4000;
  Seconds output_delay{0};        // the part's group delay from sampling to data-ready
  std::size_t window_edges = 64;  // edges in the fit (at most kMaxEdges)
  double max_rate_error = 0.10;   // a fitted rate further than this from nominal is not believed
};

class SampleClock {
 public:
  static constexpr std::size_t kMaxEdges = 256;
  explicit SampleClock(SampleClockConfig config);

  // A data-ready edge at `edge` after which `samples` new samples were read (oldest first).
  // Returns the time of the newest of them; sample i of the burst is at newest - (samples-1-i) period.
  CaptureTime edge(CaptureTime edge, std::uint32_t samples);
  Nanoseconds period() const { return Nanoseconds{static_cast<std::int64_t>(period_s_ * 1e9)}; }
  double rate_hz() const { return 1.0 / period_s_; }
  // A FIFO overflow or restart: the sample count is no longer continuous; start the fit again.
  void restart();

 private:
  struct Edge {
    double count;  // samples before this edge's newest, since the fit began
    double t_s;    // edge time, s since the fit began
  };
  void fit();

  SampleClockConfig config_;
  std::array<Edge, kMaxEdges> edges_{};
  std::size_t head_ = 0, n_ = 0;
  bool started_ = false;
  CaptureTime origin_{};
  double count_ = 0;
  double period_s_;
  double intercept_s_ = 0;  // fitted edge time at count 0
};

}  // namespace roadload::clock
