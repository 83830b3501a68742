#include <time.h>

#include <algorithm>
#include <cerrno>

#include "roadload/io/replay_clock.hpp"
#include "roadload/io/source.hpp"

namespace roadload::io {

namespace {
constexpr std::int64_t kNsPerS = 1'000'000'000;
}

const char* to_string(SourceState s) {
  switch (s) {
    case SourceState::up: return "up";
    case SourceState::waiting: return "waiting";
    case SourceState::down: return "down";
    case SourceState::ended: return "ended";
  }
  return "?";
}

CaptureTime MonotonicClock::now() const {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return capture_time_from_ns(static_cast<std::int64_t>(ts.tv_sec) * kNsPerS + ts.tv_nsec);
}

void MonotonicClock::sleep_until(CaptureTime t, Nanoseconds limit) {
  const std::int64_t target = std::min(to_ns(t), to_ns(now()) + limit.count());
  const timespec ts{static_cast<time_t>(target / kNsPerS), static_cast<long>(target % kNsPerS)};
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

}  // namespace roadload::io
