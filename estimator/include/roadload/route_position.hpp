#pragma once
// Where the truck's front axle is along the route: the wheel-speed odometer, placed on the route by
// the mean offset of every GNSS fix that lies on it. GNSS noise averages out over the fixes, the
// odometer carries the position between them, and a fix late by its receiver's latency moves the
// mean by no more than a tick's travel.
#include <cstddef>
#include <optional>

#include "roadload/route_geometry.hpp"
#include "roadload/samples.hpp"
#include "roadload/time.hpp"

namespace roadload {

class RoutePosition {
 public:
  // `antenna_behind_front_m`: where the GNSS antenna sits behind the front axle; fixes farther than
  // `max_offset_m` from the route are not on it.
  RoutePosition(double antenna_behind_front_m, double max_offset_m)
      : antenna_behind_front_m_(antenna_behind_front_m), max_offset_m_(max_offset_m) {}

  // A wheel speed at time t: the odometer moves on by it over the time since the last one.
  void advance(CaptureTime t, double speed_mps);
  // A fix places the odometer on the route: the fix's own place on it, none when the fix is off
  // it (and counted).
  std::optional<RouteGeometry::Projection> place(const GnssFix& fix, const RouteGeometry& route);

  bool placed() const { return fixes_ > 0; }
  // At the last wheel speed.
  double front_m() const { return odometer_m_ + (fixes_ > 0 ? offset_sum_m_ / static_cast<double>(fixes_) : 0.0); }
  // Carried on from the last wheel speed at that speed, for samples between wheel speeds.
  double front_m_at(CaptureTime t) const { return front_m() + speed_mps_ * to_seconds(t - t_); }
  std::size_t fixes_used() const { return fixes_; }
  std::size_t fixes_off_route() const { return off_route_; }

 private:
  double antenna_behind_front_m_;
  double max_offset_m_;
  bool moving_ = false;
  CaptureTime t_{};
  double speed_mps_ = 0;
  double odometer_m_ = 0;
  double offset_sum_m_ = 0;
  std::size_t fixes_ = 0, off_route_ = 0;
};

}  // namespace roadload
