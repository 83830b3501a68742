// A place along the route back to a point on the map: the inverse of projecting a fix onto it.
#include <gtest/gtest.h>

#include <vector>

#include "roadload/route_geometry.hpp"

namespace roadload {
namespace {

// Three points, a bend in the middle, about 1.1 km a leg.
std::vector<GeoPoint> bent_road() { return {{45.0, -93.0, 300.0}, {45.01, -93.0, 310.0}, {45.01, -92.986, 305.0}}; }

TEST(RouteGeometry, APlaceAlongItProjectsBackToItself) {
  const auto route = RouteGeometry::build(bent_road());
  ASSERT_TRUE(route);
  for (double s : {0.0, 250.0, 1000.0, 1500.0, route->length_m() - 1}) {
    const GeoPoint p = route->at(s);
    const auto back = route->project(p.lat_deg, p.lon_deg);
    EXPECT_NEAR(back.s_m, s, 0.01) << "at " << s;
    EXPECT_NEAR(back.offset_m, 0.0, 0.01) << "at " << s;
    EXPECT_NEAR(p.elev_m, route->elevation_m(s), 1e-9);
  }
  // The ends are the surveyed points, and beyond them it stays at them.
  EXPECT_NEAR(route->at(0).lat_deg, 45.0, 1e-9);
  EXPECT_NEAR(route->at(route->length_m()).lon_deg, -92.986, 1e-9);
  EXPECT_NEAR(route->at(-50).lat_deg, 45.0, 1e-9);
}

}  // namespace
}  // namespace roadload
