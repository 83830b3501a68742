#include "roadload/track_route.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
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

// A 2-D fix places the road but says nothing of its height (a bus's VP1 without VDS).
bool usable(const GnssFix& f, double max_hdop) {
  return f.mode != GnssFixMode::none && std::isfinite(f.lat_deg) && std::isfinite(f.lon_deg) && !(f.hdop > max_hdop);
}

double road_height_m(const GnssFix& f, double antenna_height_m) {
  const bool measured = f.mode == GnssFixMode::fix_3d || f.mode == GnssFixMode::dgps || f.mode == GnssFixMode::rtk;
  return measured && std::isfinite(f.alt_m) ? f.alt_m - antenna_height_m : std::numeric_limits<double>::quiet_NaN();
}

// The usable fixes as road points at least `point_spacing_m` apart.
TrackRoute thin(std::span<const GnssFix> fixes, double antenna_height_m, const TrackRouteConfig& config) {
  TrackRoute r;
  for (const GnssFix& f : fixes) {
    if (!usable(f, config.max_hdop)) continue;
    ++r.fixes_used;
    const GeoPoint p{f.lat_deg, f.lon_deg, road_height_m(f, antenna_height_m)};
    if (!r.points.empty() && distance_m(r.points.back(), p) < config.point_spacing_m) continue;
    r.points.push_back(p);
  }
  return r;
}

double length_m(std::span<const GeoPoint> points) {
  double sum = 0;
  for (std::size_t i = 1; i < points.size(); ++i) sum += distance_m(points[i - 1], points[i]);
  return sum;
}

double heading_deg(const GeoPoint& a, const GeoPoint& b) {
  const double north = b.lat_deg - a.lat_deg;
  const double east = (b.lon_deg - a.lon_deg) * std::cos(0.5 * (a.lat_deg + b.lat_deg) * std::numbers::pi / 180.0);
  return std::atan2(east, north) * 180.0 / std::numbers::pi;
}

double turn_deg(double a, double b) { return std::abs(std::remainder(b - a, 360.0)); }

// Cuts a thinned track where it turns back on itself: a segment heading against one within the
// window before it. A road's curves turn far less over so short a distance; a U-turn, a
// turnaround loop or a three-point turn do not.
std::vector<std::vector<GeoPoint>> passes_of(const std::vector<GeoPoint>& points, const TrackRouteConfig& config) {
  std::vector<std::vector<GeoPoint>> out(1);
  std::vector<double> headings;  // of the current pass's segments
  for (const GeoPoint& p : points) {
    std::vector<GeoPoint>& pass = out.back();
    if (!pass.empty()) {
      const double h = heading_deg(pass.back(), p);
      double back_m = 0;
      bool reversed = false;
      for (std::size_t k = headings.size(); k-- > 0 && back_m < config.reversal_window_m;) {
        back_m += distance_m(pass[k], pass[k + 1]);
        reversed = reversed || turn_deg(headings[k], h) > config.reversal_turn_deg;
      }
      if (reversed) {
        out.push_back({pass.back()});
        headings.clear();
      }
      headings.push_back(h);
    }
    out.back().push_back(p);
  }
  return out;
}

// Where along `road` a point is: the index of its nearest vertex.
std::size_t nearest_vertex(const std::vector<GeoPoint>& road, const GeoPoint& p) {
  std::size_t best = 0;
  for (std::size_t i = 1; i < road.size(); ++i) {
    if (distance_m(road[i], p) < distance_m(road[best], p)) best = i;
  }
  return best;
}

}  // namespace

std::optional<TrackRoute> route_from_track(std::span<const GnssFix> fixes, double antenna_height_m, const TrackRouteConfig& config) {
  TrackRoute r = thin(fixes, antenna_height_m, config);
  if (r.points.size() < 2 || length_m(r.points) < config.cell_length_m) return std::nullopt;
  return r;
}

std::optional<TrackRoute> longest_pass(std::span<const GnssTrack> tracks, const TrackRouteConfig& config) {
  TrackRoute best;
  std::vector<GeoPoint> first;
  double best_m = 0;
  std::size_t used = 0;
  for (const GnssTrack& t : tracks) {
    const TrackRoute thinned = thin(t.fixes, t.antenna_height_m, config);
    used += thinned.fixes_used;
    for (std::vector<GeoPoint>& pass : passes_of(thinned.points, config)) {
      if (pass.size() < 2) continue;
      if (first.empty()) first = pass;
      const double m = length_m(pass);
      if (m <= best_m) continue;
      best_m = m;
      best.points = std::move(pass);
    }
  }
  best.fixes_used = used;
  if (best.points.size() < 2 || best_m < config.cell_length_m) return std::nullopt;
  // A route has a direction (cells, grade and odometry run along it): the first pass's.
  if (nearest_vertex(best.points, first.back()) < nearest_vertex(best.points, first.front())) {
    std::reverse(best.points.begin(), best.points.end());
  }
  return best;
}

std::vector<SectionSpan> place_sections(const RouteGeometry& route, std::span<const std::vector<GeoPoint>> lines,
                                        double max_offset_m) {
  std::vector<SectionSpan> out;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    SectionSpan span{i, 0, 0, {}};
    if (lines[i].size() < 2) {
      span.skipped = "has fewer than two points";
      out.push_back(span);
      continue;
    }
    const auto a = route.project(lines[i].front().lat_deg, lines[i].front().lon_deg);
    const auto b = route.project(lines[i].back().lat_deg, lines[i].back().lon_deg);
    span.start_m = std::clamp(std::min(a.s_m, b.s_m), 0.0, route.length_m());
    span.end_m = std::clamp(std::max(a.s_m, b.s_m), 0.0, route.length_m());
    const double offset = std::max(a.offset_m, b.offset_m);
    if (offset > max_offset_m) {
      span.skipped = "an end lies " + std::to_string(static_cast<long>(offset)) + " m from the route";
    } else if (span.end_m - span.start_m < 1.0) {
      span.skipped = "does not lie along the route";
    }
    out.push_back(span);
  }
  std::stable_sort(out.begin(), out.end(), [](const SectionSpan& x, const SectionSpan& y) { return x.start_m < y.start_m; });
  const SectionSpan* before = nullptr;
  for (SectionSpan& s : out) {
    if (!s.skipped.empty()) continue;
    // Sections digitised end to end overlap by a few metres; more is two sections for one road.
    if (before != nullptr && s.start_m < before->end_m) {
      if (before->end_m - s.start_m > 0.5 * (s.end_m - s.start_m)) {
        s.skipped = "overlaps the section before it by more than half its length";
        continue;
      }
      s.start_m = before->end_m;
    }
    before = &s;
  }
  return out;
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
