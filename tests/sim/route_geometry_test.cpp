// The route's geometry is the geodesic polyline through its points: a place along it, and the plant's
// heading, are the geodesic from the segment's start, walked its distance, in every bit.
#include <gtest/gtest.h>

#include <GeographicLib/Geodesic.hpp>
#include <cmath>

#include "roadload/sim/route.hpp"

namespace roadload::sim {
namespace {

RouteDef bent_road() {
  RouteDef d;
  d.name = "bent";
  d.points = {{45.0, -93.0, 280.0}, {45.01, -93.0, 282.0}, {45.02, -92.98, 281.0}, {45.015, -92.95, 279.0}};
  return d;
}

TEST(RouteGeometry, PlacesAreTheGeodesicFromTheSegmentStart) {
  auto route = Route::build(bent_road());
  ASSERT_TRUE(route.ok());
  const Route& r = route.value();
  const auto& geod = GeographicLib::Geodesic::WGS84();
  const auto& pts = r.def().points;
  double start_m = 0;
  for (std::size_t i = 0; i + 1 < pts.size(); ++i) {
    double length = 0, azi1 = 0, azi2 = 0;
    geod.Inverse(pts[i].lat_deg, pts[i].lon_deg, pts[i + 1].lat_deg, pts[i + 1].lon_deg, length, azi1, azi2);
    // Run-in before the first point and past the last extends the end segments.
    const double from = i == 0 ? -500.0 : 0.0;
    const double to = i + 2 == pts.size() ? length + 500.0 : length;
    for (double ds = from; ds < to; ds += 37.3) {
      double lat = 0, lon = 0, azi = 0;
      geod.Direct(pts[i].lat_deg, pts[i].lon_deg, azi1, ds, lat, lon, azi);
      const Route::Position p = r.at(start_m + ds);
      EXPECT_EQ(p.lat_deg, lat) << "segment " << i << " at " << ds << " m";
      EXPECT_EQ(p.lon_deg, lon) << "segment " << i << " at " << ds << " m";
      EXPECT_EQ(p.heading_deg, std::fmod(azi + 360.0, 360.0)) << "segment " << i << " at " << ds << " m";
      EXPECT_EQ(r.heading_deg(start_m + ds), p.heading_deg) << "segment " << i << " at " << ds << " m";
    }
    start_m += length;
  }
  EXPECT_NEAR(r.length_m(), start_m, 1e-6);
}

}  // namespace
}  // namespace roadload::sim
