#include "roadload/track_route.hpp"

#include <cmath>
#include <numbers>

namespace roadload {
namespace {

// Metres between two nearby fixes on a sphere of the Earth's mean radius: the thinning needs
// tens of metres to a percent, not the ellipsoid's millimetres (RouteGeometry measures the route).
double distance_m(const GeoPoint& a, const GeoPoint& b) {
  constexpr double kEarthRadius_m = 6371008.8;
  constexpr double kRad = std::numbers::pi / 180.0;
  const double north = (b.lat_deg - a.lat_deg) * kRad * kEarthRadius_m;
  const double east = (b.lon_deg - a.lon_deg) * kRad * kEarthRadius_m * std::cos(0.5 * (a.lat_deg + b.lat_deg) * kRad);
  return std::hypot(north, east);
}

bool usable(const GnssFix& f, double max_hdop) {
  return (f.mode == GnssFixMode::fix_3d || f.mode == GnssFixMode::dgps || f.mode == GnssFixMode::rtk) && std::isfinite(f.lat_deg) &&
         std::isfinite(f.lon_deg) && std::isfinite(f.alt_m) && !(f.hdop > max_hdop);
}

}  // namespace

std::optional<TrackRoute> route_from_track(std::span<const GnssFix> fixes, double antenna_height_m, const TrackRouteConfig& config) {
  TrackRoute r;
  double length_m = 0;
  for (const GnssFix& f : fixes) {
    if (!usable(f, config.max_hdop)) continue;
    ++r.fixes_used;
    const GeoPoint p{f.lat_deg, f.lon_deg, f.alt_m - antenna_height_m};
    if (!r.points.empty()) {
      const double step = distance_m(r.points.back(), p);
      if (step < config.point_spacing_m) continue;
      length_m += step;
    }
    r.points.push_back(p);
  }
  if (r.points.size() < 2 || length_m < config.cell_length_m) return std::nullopt;
  return r;
}

std::vector<CellSpan> fixed_length_cells(double route_length_m, double cell_length_m) {
  std::vector<CellSpan> cells;
  for (double s = 0; s + 0.5 * cell_length_m < route_length_m || cells.empty(); s += cell_length_m) {
    const double end = s + 1.5 * cell_length_m > route_length_m ? route_length_m : s + cell_length_m;
    cells.push_back({std::to_string(static_cast<long>(s)) + " m", s, end});
    if (end >= route_length_m) break;
  }
  return cells;
}

}  // namespace roadload
