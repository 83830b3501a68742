#pragma once
// Where on the route the truck is: a surveyed polyline with elevation, distances along it on the
// WGS84 ellipsoid (GeographicLib), GNSS fixes projected onto it. The grade and its uncertainty
// come from a GradeProfile (grade_profile.hpp) built on it.
#include <array>
#include <optional>
#include <span>
#include <vector>

#include "roadload/geo_point.hpp"

namespace roadload {

class RouteGeometry {
 public:
  // Needs at least two distinct points.
  static std::optional<RouteGeometry> build(std::span<const GeoPoint> points);

  struct Projection {
    double s_m;       // along the polyline from its first point (negative before it)
    double offset_m;  // perpendicular distance from it
  };
  Projection project(double lat_deg, double lon_deg) const;

  double length_m() const { return cumulative_m_.back(); }
  double elevation_m(double s_m) const;
  // The point `s_m` along the route (clamped to its ends): where a cell starts or ends on a map.
  GeoPoint at(double s_m) const;
  double heading_deg(double s_m) const;

 private:
  std::size_t segment(double s_m) const;
  // The fix's place along segment i and its distance from it, in the segment's tangent plane.
  Projection onto(std::size_t i, double lat_deg, double lon_deg) const;
  // No more than onto(i).offset_m for a fix at Earth-centred `q`: found without a projection, so
  // that a fix is projected exactly onto the few segments near it, not onto every one of a long
  // route's. Zero for the end segments, which reach beyond their ends.
  double offset_bound_m(std::size_t i, const std::array<double, 3>& q) const;

  // The segments between the ends, in runs of kBlock, and the blocks in groups of kBlock: a point
  // within `reach_m` of each start, and the longest of them, bound a whole run from one distance,
  // so that a fix on a route of any length looks at few groups' and blocks' bounds.
  static constexpr std::size_t kBlock = 32;
  struct Block {
    std::array<double, 3> center_ecef_m;
    double reach_m, longest_m;
  };
  // offset_bound_m for every segment of a block or group at once.
  static double bound_m(const Block& k, const std::array<double, 3>& q);
  std::vector<Block> blocks_, groups_;

  // Each segment in the tangent plane at its start: its end there, and the plane's origin.
  struct Plane {
    double lat0_deg, lon0_deg, end_x_m, end_y_m;
  };
  std::vector<Plane> planes_;
  std::vector<std::array<double, 3>> start_ecef_m_;  // each segment's start, Earth-centred
  std::vector<double> plane_length_m_;               // each segment's length in its tangent plane
  std::vector<GeoPoint> points_;
  std::vector<double> cumulative_m_;
  std::vector<double> azimuth_deg_;
};

}  // namespace roadload
