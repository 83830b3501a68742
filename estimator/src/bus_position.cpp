#include "roadload/bus_position.hpp"

#include <cmath>
#include <limits>

namespace roadload {
namespace {

template <typename Bound>
Bound bind(const j1939::Database& db, const char* message, const char* signal) {
  Bound b;
  if (const j1939::MessageDef* m = db.find_name(message)) {
    for (const auto& s : m->signals) {
      if (s.name == signal) b = {m->pgn, &s};
    }
  }
  return b;
}

}  // namespace

BusPosition::BusPosition(const j1939::Database& db)
    : lat_(bind<Bound>(db, "VP1", "Latitude")), lon_(bind<Bound>(db, "VP1", "Longitude")), alt_(bind<Bound>(db, "VDS", "Altitude")) {}

std::optional<GnssFix> BusPosition::push(const j1939::Message& m) {
  if (alt_.signal != nullptr && m.pgn == alt_.pgn) {
    if (auto a = j1939::decode(*alt_.signal, m.data).get()) {
      altitude_m_ = *a;
      altitude_t_ = m.t;
    }
    return std::nullopt;
  }
  if (lat_.signal == nullptr || lon_.signal == nullptr || m.pgn != lat_.pgn) return std::nullopt;
  const auto lat = j1939::decode(*lat_.signal, m.data).get();
  const auto lon = j1939::decode(*lon_.signal, m.data).get();
  // The DBC's range runs to 211 degrees: a valid raw value can still be no place on Earth.
  if (!lat || !lon || std::abs(*lat) > 90 || std::abs(*lon) > 180) return std::nullopt;
  GnssFix f;
  f.t = m.t;
  f.lat_deg = *lat;
  f.lon_deg = *lon;
  f.speed_mps = std::numeric_limits<double>::quiet_NaN();
  f.course_deg = std::numeric_limits<double>::quiet_NaN();
  f.hdop = std::numeric_limits<double>::quiet_NaN();
  const bool with_altitude = altitude_m_ && m.t - altitude_t_ <= kMaxAltitudeAge;
  f.alt_m = with_altitude ? *altitude_m_ : std::numeric_limits<double>::quiet_NaN();
  f.mode = with_altitude ? GnssFixMode::fix_3d : GnssFixMode::fix_2d;
  return f;
}

}  // namespace roadload
