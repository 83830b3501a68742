// A road traced from a drive's own GNSS: a drive out and back is cut into its two passes at the
// turnaround, and not at a bend; a 2-D fix places the road without a height; pavement sections
// are placed on the traced road by their ends, trimmed where they overlap, refused where they lie
// elsewhere.
#include "roadload/track_route.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace roadload {
namespace {

constexpr double kLat0_deg = 45.0, kLon0_deg = -93.0;
constexpr double kMetresPerDegLat = 111132.0;
const double kMetresPerDegLon = 111320.0 * std::cos(kLat0_deg * std::numbers::pi / 180.0);

GeoPoint at(double north_m, double east_m, double elev_m = 300.0) {
  return {kLat0_deg + north_m / kMetresPerDegLat, kLon0_deg + east_m / kMetresPerDegLon, elev_m};
}

GnssFix fix(const GeoPoint& p, std::int64_t i, GnssFixMode mode = GnssFixMode::fix_3d) {
  GnssFix f;
  f.t = capture_time_from_ns(i * 100'000'000);
  f.lat_deg = p.lat_deg;
  f.lon_deg = p.lon_deg;
  f.alt_m = p.elev_m + 3.5;  // the antenna above the road
  f.mode = mode;
  f.hdop = 0.9;
  return f;
}

// North for `out_m`, a 20 m wide turnaround loop, then south for `back_m` in the next lane.
std::vector<GnssFix> out_and_back(double out_m, double back_m) {
  std::vector<GnssFix> fixes;
  std::int64_t i = 0;
  for (double s = 0; s <= out_m; s += 1.3) fixes.push_back(fix(at(s, 0), i++));
  for (double a = 0; a <= 180; a += 10) {
    const double r = std::numbers::pi * a / 180;
    fixes.push_back(fix(at(out_m + 10 * std::sin(r), 10 - 10 * std::cos(r)), i++));
  }
  for (double s = out_m; s >= out_m - back_m; s -= 1.3) fixes.push_back(fix(at(s, 20), i++));
  return fixes;
}

TEST(TrackRoute, AnOutAndBackDriveIsCutAtItsTurnaround) {
  const std::vector<GnssFix> fixes = out_and_back(1200, 900);
  const GnssTrack tracks[] = {{fixes, 3.5}};
  const auto pass = longest_pass(tracks);
  ASSERT_TRUE(pass);
  const auto geometry = RouteGeometry::build(pass->points);
  ASSERT_TRUE(geometry);
  // The outbound pass, not the two passes joined (about 2100 m) nor the shorter way back.
  EXPECT_NEAR(geometry->length_m(), 1200, 40);
  EXPECT_NEAR(pass->points.front().lat_deg, kLat0_deg, 1e-6);
  EXPECT_NEAR(pass->points.front().elev_m, 300.0, 1e-9);  // the road's height, not the antenna's
}

TEST(TrackRoute, TheRouteRunsTheWayTheFirstPassDrives) {
  // The way back (900 m) drives first, the longer outbound pass (1200 m) second: the road is the
  // outbound pass's, in the direction of the way back.
  const std::vector<GnssFix> out_back = out_and_back(1200, 900);
  const std::vector<GnssFix> back(out_back.end() - 600, out_back.end());
  const GnssTrack tracks[] = {{back, 3.5}, {out_back, 3.5}};
  const auto pass = longest_pass(tracks);
  ASSERT_TRUE(pass);
  EXPECT_NEAR(RouteGeometry::build(pass->points)->length_m(), 1200, 40);
  EXPECT_GT(pass->points.front().lat_deg, pass->points.back().lat_deg);  // southward
}

TEST(TrackRoute, ABendIsNoTurnaround) {
  // A right angle of 60 m radius: 90 degrees over 94 m, not a pass's end.
  std::vector<GnssFix> fixes;
  std::int64_t i = 0;
  for (double s = 0; s < 600; s += 1.3) fixes.push_back(fix(at(s, 0), i++));
  for (double a = 0; a < 90; a += 2) {
    const double r = std::numbers::pi * a / 180;
    fixes.push_back(fix(at(600 + 60 * std::sin(r), 60 - 60 * std::cos(r)), i++));
  }
  for (double e = 60; e < 700; e += 1.3) fixes.push_back(fix(at(660, e), i++));
  const GnssTrack tracks[] = {{fixes, 3.5}};
  const auto pass = longest_pass(tracks);
  ASSERT_TRUE(pass);
  EXPECT_NEAR(RouteGeometry::build(pass->points)->length_m(), 600 + 94 + 640, 30);
}

TEST(TrackRoute, TwoDimensionalFixesPlaceTheRoadWithoutAHeight) {
  std::vector<GnssFix> fixes;
  for (std::int64_t i = 0; i < 400; ++i) fixes.push_back(fix(at(static_cast<double>(i), 0), i, GnssFixMode::fix_2d));
  const auto r = route_from_track(fixes, 3.5);
  ASSERT_TRUE(r);
  EXPECT_EQ(r->fixes_used, 400u);
  for (const GeoPoint& p : r->points) EXPECT_TRUE(std::isnan(p.elev_m));
}

TEST(TrackRoute, SectionsArePlacedByTheirEndsInOrderAlongTheRoad) {
  const auto route = RouteGeometry::build(std::vector<GeoPoint>{at(0, 0), at(1000, 0)});
  ASSERT_TRUE(route);
  const std::vector<std::vector<GeoPoint>> lines = {
      {at(597, 2), at(1000, 1)},                                // drawn first, lies last, overlaps the one before by 3 m
      {at(400, -1), at(0, 0)},                                  // drawn against the route's direction
      {at(400, 1), at(600, 0)},  {at(300, 300), at(500, 300)},  // another road
      {at(200, 0), at(380, 0)},                                 // mostly the first section again
  };
  const std::vector<SectionSpan> spans = place_sections(*route, lines, 15.0);
  ASSERT_EQ(spans.size(), 5u);
  std::vector<std::size_t> placed;
  for (const SectionSpan& s : spans) {
    if (s.skipped.empty()) placed.push_back(s.index);
  }
  EXPECT_EQ(placed, (std::vector<std::size_t>{1, 2, 0}));
  const auto span = [&](std::size_t index) {
    for (const SectionSpan& s : spans) {
      if (s.index == index) return s;
    }
    return SectionSpan{};
  };
  EXPECT_NEAR(span(1).start_m, 0, 0.5);
  EXPECT_NEAR(span(1).end_m, 400, 0.5);
  EXPECT_NEAR(span(2).end_m, 600, 0.5);
  EXPECT_NEAR(span(0).start_m, 600, 0.5);  // trimmed to where the one before ends
  EXPECT_NE(span(3).skipped.find("from the route"), std::string::npos) << span(3).skipped;
  EXPECT_NE(span(4).skipped.find("overlaps"), std::string::npos) << span(4).skipped;
}

TEST(TrackRoute, FixedCellsCoverTheRoadAndTheLastTakesTheRest) {
  const auto cells = fixed_length_cells(1120, 250);
  ASSERT_EQ(cells.size(), 4u);
  EXPECT_DOUBLE_EQ(cells.back().start_m, 750);
  EXPECT_DOUBLE_EQ(cells.back().end_m, 1120);
}

}  // namespace
}  // namespace roadload
