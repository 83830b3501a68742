#pragma once
// When roadloadd's writer and estimator threads wake, and when a lagging source stops holding them
// back: the policy both follow over their rings (DaemonSources).
#include <algorithm>
#include <cstddef>
#include <cstdint>

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

// How long a worker sleeps after a round that took `took` items, less than a batch, `since` after
// the round before began: kIdleSleep, less when items come so fast that kIdleSleep of them would
// fill a quarter of the smallest CAN or accelerometer ring (a replay's too), and kBusySleep while
// one already is a quarter full. On a truck's bus the rings hold seconds and it is always
// kIdleSleep; a replay at full speed, 300,000 frames/s, fills a ring in 100 ms. GNSS and weather
// rings hold their items for seconds by design (kMaxPlaceWait) and come too slowly to fill.
template <typename RingOf>
Nanoseconds idle_sleep(DaemonSources& sources, RingOf ring_of, std::size_t took, Nanoseconds since) {
  bool filling = false;
  std::size_t quarter = SIZE_MAX;
  auto look = [&](auto& c) {
    const auto& ring = ring_of(*c);
    quarter = std::min(quarter, ring.capacity() / 4);
    filling = filling || ring.size() >= ring.capacity() / 4;
  };
  std::for_each(sources.can.begin(), sources.can.end(), look);
  std::for_each(sources.accel.begin(), sources.accel.end(), look);
  if (filling) return kBusySleep;
  if (took == 0 || since <= Nanoseconds{0}) return kIdleSleep;
  // The rate summed over the rings stands for each one's: a shorter sleep, never a longer one.
  const double fill_ns = static_cast<double>(quarter) * static_cast<double>(since.count()) / static_cast<double>(took);
  return std::clamp(Nanoseconds{static_cast<std::int64_t>(std::min(fill_ns, 1e18))}, kBusySleep, kIdleSleep);
}

}  // namespace roadload::firmware
