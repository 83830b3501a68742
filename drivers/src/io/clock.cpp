#include <time.h>

#include <algorithm>
#include <cerrno>

#include "roadload/io/posix_time.hpp"
#include "roadload/io/replay_clock.hpp"
#include "roadload/io/source.hpp"

namespace roadload::io {

const char* to_string(SourceState s) {
  switch (s) {
    case SourceState::up: return "up";
    case SourceState::waiting: return "waiting";
    case SourceState::down: return "down";
    case SourceState::ended: return "ended";
  }
  return "?";
}

CaptureTime MonotonicClock::now() const { return CaptureTime{read_clock(CLOCK_MONOTONIC)}; }

void MonotonicClock::sleep_until(CaptureTime t, Nanoseconds limit) {
  const CaptureTime now_t = now();
  // A deadline already past still puts the thread through the scheduler in clock_nanosleep.
  if (t <= now_t || limit <= Nanoseconds{0}) return;
  const timespec ts = to_timespec(std::min(t, now_t + limit).time_since_epoch());
  while (clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

}  // namespace roadload::io
