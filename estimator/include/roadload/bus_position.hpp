#pragma once
// Position from the truck's own bus, for a logger with no GNSS receiver of its own: VP1 (PGN
// 65267: latitude and longitude) and, where sent, VDS (PGN 65256: altitude). A VP1 with an
// altitude at most `max_altitude_age` old is a 3-D fix, else a 2-D one (geometry, no grade).
// These receivers are coarse (metres, often without DGPS) and the fix carries no hdop.
#include <optional>

#include "roadload/j1939/assembler.hpp"
#include "roadload/j1939/database.hpp"
#include "roadload/samples.hpp"
#include "roadload/time.hpp"

namespace roadload {

class BusPosition {
 public:
  explicit BusPosition(const j1939::Database& db);
  // The fix a VP1 message makes; none for any other message or a VP1 with no valid position.
  std::optional<GnssFix> push(const j1939::Message& m);

 private:
  struct Bound {
    j1939::Pgn pgn = 0;
    const j1939::SignalDef* signal = nullptr;
  };
  Bound lat_, lon_, alt_;
  std::optional<double> altitude_m_;
  CaptureTime altitude_t_{};
  static constexpr Nanoseconds kMaxAltitudeAge = std::chrono::milliseconds(1500);
};

}  // namespace roadload
