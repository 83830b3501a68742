#include "roadload/route_geometry.hpp"

#include <GeographicLib/Geocentric.hpp>
#include <GeographicLib/Geodesic.hpp>
#include <GeographicLib/LocalCartesian.hpp>
#include <algorithm>
#include <cmath>
#include <limits>

namespace roadload {

namespace {

double distance_m(const std::array<double, 3>& a, const std::array<double, 3>& b) {
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

// How far from a segment's start a point at `chord_m` lies, at least, in the start's tangent plane:
// the chord tilted by the Earth's curvature (by asin(chord / 2R), R no less than 6,300 km on the
// ellipsoid), less 1 % for the ellipsoid. It grows with the chord up to kMonotonicM.
constexpr double kMonotonicM = 8.9e6;
double in_plane_at_least_m(double chord_m) {
  const double tilt = chord_m / (2 * 6.3e6);
  return 0.99 * chord_m * std::sqrt(std::max(0.0, 1 - tilt * tilt));
}

}  // namespace

std::optional<RouteGeometry> RouteGeometry::build(std::span<const GeoPoint> points) {
  if (points.size() < 2) return std::nullopt;
  const auto& geod = GeographicLib::Geodesic::WGS84();
  RouteGeometry g;
  g.points_.assign(points.begin(), points.end());
  g.cumulative_m_.push_back(0.0);
  for (std::size_t i = 0; i + 1 < points.size(); ++i) {
    double s12 = 0, azi1 = 0, azi2 = 0;
    geod.Inverse(points[i].lat_deg, points[i].lon_deg, points[i + 1].lat_deg, points[i + 1].lon_deg, s12, azi1, azi2);
    if (s12 < 1e-3) return std::nullopt;
    g.cumulative_m_.push_back(g.cumulative_m_.back() + s12);
    g.azimuth_deg_.push_back(azi1);
    const GeographicLib::LocalCartesian plane(points[i].lat_deg, points[i].lon_deg, 0.0);
    double ex = 0, ey = 0, ez = 0;
    plane.Forward(points[i + 1].lat_deg, points[i + 1].lon_deg, 0.0, ex, ey, ez);
    g.planes_.push_back({points[i].lat_deg, points[i].lon_deg, ex, ey});
    g.plane_length_m_.push_back(std::hypot(ex, ey));
    std::array<double, 3> start{};
    GeographicLib::Geocentric::WGS84().Forward(points[i].lat_deg, points[i].lon_deg, 0.0, start[0], start[1], start[2]);
    g.start_ecef_m_.push_back(start);
  }
  // Blocks of the segments between the ends (1 .. n-2), each about its middle segment's start.
  const std::size_t n = g.planes_.size();
  for (std::size_t first = 1; first + 1 < n; first += kBlock) {
    const std::size_t last = std::min(first + kBlock, n - 1);
    Block b{g.start_ecef_m_[(first + last) / 2], 0.0, 0.0};
    for (std::size_t i = first; i < last; ++i) {
      b.reach_m = std::max(b.reach_m, distance_m(g.start_ecef_m_[i], b.center_ecef_m));
      b.longest_m = std::max(b.longest_m, g.plane_length_m_[i]);
    }
    g.blocks_.push_back(b);
  }
  for (std::size_t first = 0; first < g.blocks_.size(); first += kBlock) {
    const std::size_t last = std::min(first + kBlock, g.blocks_.size());
    Block k{g.blocks_[(first + last) / 2].center_ecef_m, 0.0, 0.0};
    for (std::size_t b = first; b < last; ++b) {
      k.reach_m = std::max(k.reach_m, distance_m(g.blocks_[b].center_ecef_m, k.center_ecef_m) + g.blocks_[b].reach_m);
      k.longest_m = std::max(k.longest_m, g.blocks_[b].longest_m);
    }
    g.groups_.push_back(k);
  }
  return g;
}

std::size_t RouteGeometry::segment(double s_m) const {
  if (s_m <= 0) return 0;
  if (s_m >= cumulative_m_.back()) return azimuth_deg_.size() - 1;
  return static_cast<std::size_t>(std::upper_bound(cumulative_m_.begin(), cumulative_m_.end(), s_m) - cumulative_m_.begin()) - 1;
}

RouteGeometry::Projection RouteGeometry::onto(std::size_t i, double lat_deg, double lon_deg) const {
  // Each segment in the tangent plane at its start: exact enough for survey spacing of < 1 km.
  const Plane& pl = planes_[i];
  const double ex = pl.end_x_m, ey = pl.end_y_m;
  double px = 0, py = 0, pz = 0;
  GeographicLib::LocalCartesian(pl.lat0_deg, pl.lon0_deg, 0.0).Forward(lat_deg, lon_deg, 0.0, px, py, pz);
  const double len2 = ex * ex + ey * ey;
  double t = (px * ex + py * ey) / len2;
  // The first and last segments extend beyond the ends, so a truck running in is placed.
  if (i > 0) t = std::max(t, 0.0);
  if (i + 2 < points_.size()) t = std::min(t, 1.0);
  return {cumulative_m_[i] + t * (cumulative_m_[i + 1] - cumulative_m_[i]), std::hypot(px - t * ex, py - t * ey)};
}

double RouteGeometry::offset_bound_m(std::size_t i, const std::array<double, 3>& q) const {
  if (i == 0 || i + 2 >= points_.size()) return 0.0;
  // The segment reaches no further from its start than its length.
  return in_plane_at_least_m(distance_m(q, start_ecef_m_[i])) - plane_length_m_[i] - 1e-3;
}

double RouteGeometry::bound_m(const Block& k, const std::array<double, 3>& q) {
  // Every start lies within reach of the centre: its chord is at least this one's less the reach.
  const double nearest_m = distance_m(q, k.center_ecef_m) - k.reach_m;
  if (nearest_m <= 0 || nearest_m + 2 * k.reach_m > kMonotonicM) return 0.0;
  return in_plane_at_least_m(nearest_m) - k.longest_m - 1e-3;
}

RouteGeometry::Projection RouteGeometry::project(double lat_deg, double lon_deg) const {
  std::array<double, 3> q{};
  GeographicLib::Geocentric::WGS84().Forward(lat_deg, lon_deg, 0.0, q[0], q[1], q[2]);
  // The ends and the nearest segment of the nearest block by the bounds give a distance; only the
  // segments whose bound is within it can be nearer. The result is the one every segment's
  // projection would give: the smallest offset, the first segment of equal ones.
  const std::size_t last = planes_.size() - 1;
  // Block b holds the segments [1 + b kBlock, its end): those between the route's ends; group g
  // the blocks [g kBlock, its end).
  const auto end_of = [&](std::size_t b) { return std::min(1 + (b + 1) * kBlock, last); };
  const auto blocks_end = [&](std::size_t g) { return std::min((g + 1) * kBlock, blocks_.size()); };
  // The first of [from, to) whose bound is least.
  const auto nearest = [&](std::size_t from, std::size_t to, auto&& bound) {
    std::size_t best = from;
    double best_bound = bound(from);
    for (std::size_t i = from + 1; i < to; ++i) {
      const double b = bound(i);
      if (b < best_bound) best = i, best_bound = b;
    }
    return best;
  };
  const Projection first_end = onto(0, lat_deg, lon_deg), last_end = onto(last, lat_deg, lon_deg);
  double within_m = std::min(first_end.offset_m, last_end.offset_m);
  if (!blocks_.empty()) {
    const std::size_t g = nearest(0, groups_.size(), [&](std::size_t i) { return bound_m(groups_[i], q); });
    const std::size_t b = nearest(g * kBlock, blocks_end(g), [&](std::size_t i) { return bound_m(blocks_[i], q); });
    const std::size_t guess = nearest(1 + b * kBlock, end_of(b), [&](std::size_t i) { return offset_bound_m(i, q); });
    within_m = std::min(within_m, onto(guess, lat_deg, lon_deg).offset_m);
  }
  Projection best = first_end;
  for (std::size_t g = 0; g < groups_.size(); ++g) {
    if (bound_m(groups_[g], q) > within_m) continue;
    for (std::size_t b = g * kBlock; b < blocks_end(g); ++b) {
      if (bound_m(blocks_[b], q) > within_m) continue;
      for (std::size_t i = 1 + b * kBlock; i < end_of(b); ++i) {
        if (offset_bound_m(i, q) > within_m) continue;
        const Projection p = onto(i, lat_deg, lon_deg);
        if (p.offset_m < best.offset_m) best = p;
      }
    }
  }
  if (last_end.offset_m < best.offset_m) best = last_end;
  return best;
}

double RouteGeometry::elevation_m(double s_m) const {
  const std::size_t i = segment(s_m);
  const double len = cumulative_m_[i + 1] - cumulative_m_[i];
  const double w = std::clamp((s_m - cumulative_m_[i]) / len, 0.0, 1.0);
  return points_[i].elev_m + w * (points_[i + 1].elev_m - points_[i].elev_m);
}

GeoPoint RouteGeometry::at(double s_m) const {
  const std::size_t i = segment(s_m);
  const double len = cumulative_m_[i + 1] - cumulative_m_[i];
  const double w = std::clamp((s_m - cumulative_m_[i]) / len, 0.0, 1.0);
  const Plane& pl = planes_[i];
  GeoPoint p;
  double h = 0;
  GeographicLib::LocalCartesian(pl.lat0_deg, pl.lon0_deg, 0.0).Reverse(w * pl.end_x_m, w * pl.end_y_m, 0.0, p.lat_deg, p.lon_deg, h);
  p.elev_m = elevation_m(s_m);
  return p;
}

double RouteGeometry::heading_deg(double s_m) const { return azimuth_deg_[segment(s_m)]; }

}  // namespace roadload
