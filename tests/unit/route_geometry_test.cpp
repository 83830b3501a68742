// A place along the route back to a point on the map: the inverse of projecting a fix onto it.
#include <gtest/gtest.h>

#include <GeographicLib/Geocentric.hpp>
#include <array>
#include <cmath>
#include <random>
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

// A mountain road of 2,001 points: forty hairpins whose legs, 2 km long, lie 60 m apart.
std::vector<GeoPoint> hairpins() {
  std::vector<GeoPoint> pts;
  constexpr double kLegDeg = 2000.0 / 111'320.0, kApartDeg = 60.0 / (111'320.0 * 0.7071);
  for (int leg = 0; leg < 40; ++leg) {
    for (int k = 0; k < 50; ++k) {
      const double along = (leg % 2 == 0 ? k : 49 - k) / 49.0 * kLegDeg;
      pts.push_back({45.0 + along, -93.0 + leg * kApartDeg, 300.0 + leg});
    }
  }
  pts.push_back({45.0 - 0.001, -93.0 + 39 * kApartDeg, 340.0});  // the last leg runs south, and on
  return pts;
}

TEST(RouteGeometry, AFixIsPlacedOnTheNearestLegOfAWindingRoad) {
  const auto route = RouteGeometry::build(hairpins());
  ASSERT_TRUE(route);
  for (double s = 500; s < route->length_m() - 500; s += 1234.5) {
    const GeoPoint p = route->at(s);
    // 20 m east of the road: nearer this leg than its neighbours, 60 m away.
    const double east_deg = 20.0 / (111'320.0 * std::cos(p.lat_deg * M_PI / 180));
    const auto off = route->project(p.lat_deg, p.lon_deg + east_deg);
    EXPECT_NEAR(off.offset_m, 20.0, 0.1) << "at " << s;
    EXPECT_NEAR(off.s_m, s, 0.5) << "at " << s;
  }
  // Far from the road (another continent, the antipode) a fix still gets the nearest place.
  const auto far = route->project(-33.9, 151.2);
  EXPECT_GT(far.offset_m, 1e6);
  EXPECT_TRUE(std::isfinite(far.s_m));
  const auto antipode = route->project(-45.0, 87.0);
  EXPECT_TRUE(std::isfinite(antipode.offset_m));
}

// Against the road drawn every half metre: a fix up to 300 m off any leg is as far from the road as
// the nearest drawn point (to the drawing's quarter metre), whichever leg or hairpin that is.
TEST(RouteGeometry, AFixIsAsFarAsTheNearestPointOfTheRoad) {
  const auto route = RouteGeometry::build(hairpins());
  ASSERT_TRUE(route);
  const auto& earth = GeographicLib::Geocentric::WGS84();
  const auto ecef = [&](double lat, double lon) {
    std::array<double, 3> e{};
    earth.Forward(lat, lon, 0.0, e[0], e[1], e[2]);
    return e;
  };
  std::vector<std::array<double, 3>> drawn;
  for (double s = 0; s <= route->length_m(); s += 0.5) {
    const GeoPoint p = route->at(s);
    drawn.push_back(ecef(p.lat_deg, p.lon_deg));
  }
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> along(100.0, route->length_m() - 100.0), across(-300.0, 300.0);
  for (int k = 0; k < 300; ++k) {
    const GeoPoint p = route->at(along(rng));
    const double lon = p.lon_deg + across(rng) / (111'320.0 * std::cos(p.lat_deg * M_PI / 180));
    const auto q = ecef(p.lat_deg, lon);
    double nearest = 1e300;
    for (const auto& d : drawn) nearest = std::min(nearest, std::hypot(q[0] - d[0], q[1] - d[1], q[2] - d[2]));
    EXPECT_NEAR(route->project(p.lat_deg, lon).offset_m, nearest, 0.3) << "fix " << k;
  }
}

}  // namespace
}  // namespace roadload
