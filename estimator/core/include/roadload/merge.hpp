#pragma once
// Streams each in stamp order merge into one by taking the oldest head each time. A tie goes to the
// stream listed first (a recording's order: CAN, accelerometers, GNSS, weather), so a merge comes
// out the same whichever stream delivered first. The recording reader, roadloadd's writer and
// estimator, and the gap diagnosis's simulated streams all merge this way.
#include <cstddef>
#include <optional>

#include "roadload/time.hpp"

namespace roadload {

// `head(i)` is stream i's oldest pending stamp, or nullopt when it has none now.
template <typename Head>
std::optional<std::size_t> oldest_head(std::size_t streams, Head&& head) {
  std::optional<std::size_t> best;
  CaptureTime best_t{};
  for (std::size_t i = 0; i < streams; ++i) {
    const std::optional<CaptureTime> t = head(i);
    if (t && (!best || *t < best_t)) {
      best = i;
      best_t = *t;
    }
  }
  return best;
}

}  // namespace roadload
