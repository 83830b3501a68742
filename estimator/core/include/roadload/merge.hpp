#pragma once
// Streams each in stamp order merge into one by taking the oldest head each time. A tie goes to the
// stream listed first (a recording's order: CAN, accelerometers, GNSS, weather), so a merge comes
// out the same whichever stream delivered first. The recording reader, roadloadd's writer and
// estimator, and the gap diagnosis's simulated streams all merge this way.
#include <cstddef>
#include <optional>

#include "roadload/time.hpp"

namespace roadload {

// `pending(i)`: whether stream i has a head now; `stamp(i)`: that head's stamp, asked only when it
// has one. Two plain answers rather than an optional stamp: GCC spills an optional through the
// stack, and the stall cost the FLAC reader's merge 120 ns a sample.
template <typename Pending, typename Stamp>
std::optional<std::size_t> oldest_head(std::size_t streams, Pending&& pending, Stamp&& stamp) {
  std::size_t best = streams;
  CaptureTime best_t{};
  for (std::size_t i = 0; i < streams; ++i) {
    if (!pending(i)) continue;
    const CaptureTime t = stamp(i);
    if (best == streams || t < best_t) {
      best = i;
      best_t = t;
    }
  }
  if (best == streams) return std::nullopt;
  return best;
}

}  // namespace roadload
