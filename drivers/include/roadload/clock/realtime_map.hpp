#pragma once
// Kernel receive stamps of CAN_RAW sockets (SO_TIMESTAMPING, software) are CLOCK_REALTIME; the
// capture clock is CLOCK_MONOTONIC. NTP slews both alike, so their difference only changes when
// the wall clock is stepped (NTP, GNSS, an operator). The map keeps the last few offsets, each from
// the tightest of repeated readings of both clocks, and places a stamp with the offset that puts it
// where it can be: at or shortly before the moment the daemon read the frame. A step between a
// frame's arrival and its read therefore neither shifts nor reorders it, provided the daemon reads
// both clocks after each receive (observe) and the step is larger than the frame's wait plus
// future_slack_ns: a backward step of 2 ms on a frame that waited 3 ms fits either offset.
// An offset also places any stamp after its own first reading, however long the frame waited: no
// step came between, and a frame stamped before a forward step lands before that reading. So the
// frames queued between the socket's opening (its first reading) and a slow start of the daemon
// keep their kernel stamps.
//
// Pure computation: the caller reads the clocks (drivers/socketcan) and passes the numbers in.
#include <array>
#include <cstdint>
#include <optional>

#include "roadload/time.hpp"

namespace roadload::clock {

// Three readings taken back to back: monotonic, realtime, monotonic.
struct ClockReading {
  std::int64_t mono_before_ns = 0;
  std::int64_t realtime_ns = 0;
  std::int64_t mono_after_ns = 0;
};

struct RealtimeMapConfig {
  std::int64_t step_threshold_ns = 200'000;   // an offset change beyond this is a step, not read noise
  std::int64_t max_latency_ns = 500'000'000;  // a frame read later waits at most this long in the socket
  std::int64_t future_slack_ns = 1'000'000;   // how far past its read a mapped stamp may land (offset error)
};

struct RealtimeMapCounters {
  std::uint64_t readings = 0;
  std::uint64_t steps = 0;     // wall-clock steps seen
  std::uint64_t unplaced = 0;  // stamps no kept offset could place
};

class RealtimeMap {
 public:
  explicit RealtimeMap(RealtimeMapConfig config = {}) : config_(config) {}

  void observe(const ClockReading& r);
  bool ready() const { return count_ > 0; }
  // The capture time of a realtime stamp of a frame the daemon read at monotonic `read_mono_ns`;
  // nothing when no kept offset places it within [min(read - max_latency, the offset's first
  // reading), read + slack].
  std::optional<CaptureTime> map(std::int64_t realtime_ns, std::int64_t read_mono_ns);
  // realtime - monotonic now, as last measured.
  std::int64_t offset_ns() const { return epochs_[newest()].offset_ns; }
  const RealtimeMapCounters& counters() const { return counters_; }

 private:
  struct Epoch {
    std::int64_t offset_ns = 0;       // realtime - monotonic
    std::int64_t uncertainty_ns = 0;  // half the tightest reading's monotonic interval
    std::int64_t first_mono_ns = 0;   // when this offset was first read: it held from then on
  };
  static constexpr std::size_t kEpochs = 8;
  std::size_t newest() const { return (head_ + kEpochs - 1) % kEpochs; }

  RealtimeMapConfig config_;
  std::array<Epoch, kEpochs> epochs_{};
  std::size_t head_ = 0, count_ = 0;
  RealtimeMapCounters counters_;
};

}  // namespace roadload::clock
