#include "roadload/clock/realtime_map.hpp"

#include <algorithm>
#include <cstdlib>

namespace roadload::clock {

void RealtimeMap::observe(const ClockReading& r) {
  ++counters_.readings;
  const std::int64_t half = (r.mono_after_ns - r.mono_before_ns) / 2;
  if (half < 0) return;  // not a reading of a monotonic clock
  const Epoch e{r.realtime_ns - (r.mono_before_ns + half), half, r.mono_after_ns};
  if (count_ > 0) {
    Epoch& cur = epochs_[newest()];
    const std::int64_t change = std::llabs(e.offset_ns - cur.offset_ns);
    if (change <= config_.step_threshold_ns + cur.uncertainty_ns + e.uncertainty_ns) {
      if (e.uncertainty_ns < cur.uncertainty_ns) {  // a tighter reading of the same offset
        cur.offset_ns = e.offset_ns;
        cur.uncertainty_ns = e.uncertainty_ns;
      }
      return;
    }
    ++counters_.steps;
  }
  epochs_[head_] = e;
  head_ = (head_ + 1) % kEpochs;
  if (count_ < kEpochs) ++count_;
}

std::optional<CaptureTime> RealtimeMap::map(std::int64_t realtime_ns, std::int64_t read_mono_ns) {
  for (std::size_t i = 0; i < count_; ++i) {
    const Epoch& e = epochs_[(head_ + kEpochs - 1 - i) % kEpochs];
    const std::int64_t t = realtime_ns - e.offset_ns;
    const std::int64_t earliest = std::min(read_mono_ns - config_.max_latency_ns, e.first_mono_ns);
    if (t <= read_mono_ns + config_.future_slack_ns && t >= earliest) return capture_time_from_ns(t);
  }
  ++counters_.unplaced;
  return std::nullopt;
}

}  // namespace roadload::clock
