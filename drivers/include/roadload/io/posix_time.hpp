#pragma once
// The one place the kernel's struct timespec meets the project's time types: stamps and clock
// readings come in as Nanoseconds, waits go out as timespec.
#include <time.h>

#include "roadload/time.hpp"

namespace roadload::io {

constexpr Nanoseconds from_timespec(const timespec& ts) {
  return Nanoseconds{static_cast<std::int64_t>(ts.tv_sec) * kNsPerS + ts.tv_nsec};
}

// Negative durations are whole seconds down and a non-negative remainder, as the kernel wants.
constexpr timespec to_timespec(Nanoseconds d) {
  std::int64_t s = d.count() / kNsPerS, ns = d.count() % kNsPerS;
  if (ns < 0) {
    --s;
    ns += kNsPerS;
  }
  return timespec{static_cast<time_t>(s), static_cast<long>(ns)};
}

// clock_gettime of `id` (CLOCK_MONOTONIC, CLOCK_REALTIME, ...).
inline Nanoseconds read_clock(clockid_t id) {
  timespec ts{};
  clock_gettime(id, &ts);
  return from_timespec(ts);
}

}  // namespace roadload::io
