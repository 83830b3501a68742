#pragma once
// When roadloadd's writer and estimator threads wake, and when a lagging source stops holding them
// back: the policy both follow over their rings (DaemonSources).
#include <algorithm>
#include <cstddef>

#include "roadload/firmware/daemon.hpp"
#include "roadload/time.hpp"

namespace roadload::firmware {

// The writer and the estimator wake this often when their rings hold less than a batch. Each
// wake-up costs a gateway more than the items it takes (bench_daemon: 10 ms cost 1.2 % of a core
// more than 50 ms); the rings hold seconds and a status line is 100 ms apart.
constexpr Nanoseconds kIdleSleep{50'000'000};
constexpr std::size_t kWriteBatch = 4096;
// The wake-up instead while a ring is a quarter full or more: a bus far faster than a truck's (a
// replay at full speed, 300,000 frames/s) fills the rest of a ring in less than kIdleSleep.
constexpr Nanoseconds kBusySleep{2'000'000};

// A source that lags while it reads (a starved thread catching up, a replay slower than asked)
// holds the others back only while the devices' rings have room: once one is half full the horizon
// is lifted, and the lagging source's items go out of order rather than a device's being dropped.
// A replay's full ring lifts nothing: it waits for room, and nothing is lost by waiting.
template <typename RingOf>
bool any_half_full(DaemonSources& sources, RingOf ring_of) {
  bool full = false;
  sources.for_each([&](auto& c) {
    const auto& ring = ring_of(c);
    full = full || (!c.waits_for_room() && ring.size() >= ring.capacity() / 2);
  });
  return full;
}

// How long a worker sleeps after a round that took `took` items, less than a batch: kIdleSleep, or
// kBusySleep while it is taking items and a CAN or accelerometer ring (a replay's too) is a quarter
// full, so that none fills while it sleeps. A round that took nothing is held back by the merge's
// horizon, or nothing came: waking sooner would not help. GNSS and weather rings hold their items
// for seconds by design (kMaxPlaceWait) and come too slowly to fill.
template <typename RingOf>
Nanoseconds idle_sleep(DaemonSources& sources, RingOf ring_of, std::size_t took) {
  if (took == 0) return kIdleSleep;
  bool filling = false;
  auto look = [&](auto& c) {
    const auto& ring = ring_of(*c);
    filling = filling || ring.size() >= ring.capacity() / 4;
  };
  std::for_each(sources.can.begin(), sources.can.end(), look);
  std::for_each(sources.accel.begin(), sources.accel.end(), look);
  return filling ? kBusySleep : kIdleSleep;
}

}  // namespace roadload::firmware
