#include "roadload/route_position.hpp"

namespace roadload {

void RoutePosition::advance(CaptureTime t, double speed_mps) {
  if (moving_) odometer_m_ += speed_mps * to_seconds(t - t_);
  moving_ = true;
  t_ = t;
  speed_mps_ = speed_mps;
}

std::optional<RouteGeometry::Projection> RoutePosition::place(const GnssFix& fix, const RouteGeometry& route) {
  const RouteGeometry::Projection p = route.project(fix.lat_deg, fix.lon_deg);
  if (p.offset_m > max_offset_m_) {
    ++off_route_;
    return std::nullopt;
  }
  offset_sum_m_ += p.s_m + antenna_behind_front_m_ - odometer_m_;
  ++fixes_;
  return p;
}

}  // namespace roadload
