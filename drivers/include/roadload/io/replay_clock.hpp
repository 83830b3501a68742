#pragma once
// Replay sources hand out a recording's samples as if they were arriving now. One ReplayTiming is
// shared by every replay source of a daemon so that their streams stay aligned with each other and
// with CAN frames replayed onto a vcan interface from the same origin.
#include <cstdint>

#include "roadload/time.hpp"

namespace roadload::io {

// The daemon's view of the capture clock: CLOCK_MONOTONIC on a gateway, virtual time in tests.
class WaitClock {
 public:
  virtual ~WaitClock() = default;
  virtual CaptureTime now() const = 0;
  // Returns at `t` or earlier if `t` is further than `limit` from now (so readers stay responsive).
  virtual void sleep_until(CaptureTime t, Nanoseconds limit) = 0;
};

// CLOCK_MONOTONIC with clock_nanosleep.
class MonotonicClock final : public WaitClock {
 public:
  CaptureTime now() const override;
  void sleep_until(CaptureTime t, Nanoseconds limit) override;
};

// recorded time -> capture time: capture = capture_origin + (recorded - recorded_origin) / rate.
// rate 0 replays as fast as the reader takes it, keeping the recorded spacing in the stamps.
struct ReplayTiming {
  CaptureTime recorded_origin{};
  CaptureTime capture_origin{};
  double rate = 1.0;

  CaptureTime capture(CaptureTime recorded) const {
    const auto since = recorded - recorded_origin;
    if (rate <= 0.0 || rate == 1.0) return capture_origin + since;
    return capture_origin + Nanoseconds{static_cast<std::int64_t>(static_cast<double>(since.count()) / rate)};
  }
  // The inverse, for a paced replay: where on the recording's timeline a capture time falls.
  CaptureTime recorded(CaptureTime capture) const {
    const auto since = capture - capture_origin;
    if (rate <= 0.0 || rate == 1.0) return recorded_origin + since;
    return recorded_origin + Nanoseconds{static_cast<std::int64_t>(static_cast<double>(since.count()) * rate)};
  }
  bool paced() const { return rate > 0.0; }
};

}  // namespace roadload::io
